"""Makes the report's modules (report/: results.py and the rest) importable by the paper-table
scripts beside this file: each imports this module before `import results`."""
import os
import sys

REPORT_DIR = os.path.join(os.path.dirname(os.path.dirname(os.path.abspath(__file__))), "report")
if REPORT_DIR not in sys.path:
    sys.path.insert(0, REPORT_DIR)
