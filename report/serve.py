#!/usr/bin/python3
"""`hybridlab view RESULTS [--report DIR] [--port N]`: serves a result set and its report to a
browser on this machine (127.0.0.1 only), as tev and Jupyter do, since a page opened from the file
system may not read files: the viewer reads the result set's images itself. Prints the addresses
of the report and the viewer, and serves until Ctrl-C. Only files under RESULTS and the report
folder are served, read-only.

    serve.py RESULTS [--report DIR] [--port N]     (N = 0: any free port; the default 8765)"""
import argparse
import functools
import http.server
import os
import sys
import urllib.parse

DEFAULT_PORT = 8765


class ResultSetHandler(http.server.SimpleHTTPRequestHandler):
    """Files under `roots` (real paths) from the folder served; anything else is not found."""

    roots = ()

    def translate_path(self, path):
        local = os.path.realpath(super().translate_path(path))
        if any(local == r or local.startswith(r + os.sep) for r in self.roots):
            return local
        return os.path.join(self.directory, "\0not-served")  # no such file: 404

    def copyfile(self, source, outputfile):
        # The kernel copies the file to the socket: an EXR of the paper configs' size is megabytes.
        outputfile.flush()
        self.connection.sendfile(source)

    def end_headers(self):
        # The result set changes when the runner resumes or the report is redrawn.
        self.send_header("Cache-Control", "no-cache")
        super().end_headers()

    def log_message(self, format, *args):  # noqa: A002 (the base class's name)
        pass  # one line a request would bury the addresses printed at the start


def fail(message, status):
    print("hybridlab: error: %s" % message, file=sys.stderr)
    sys.exit(status)


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("results")
    ap.add_argument("--report", help="the report folder (default: RESULTS/report)")
    ap.add_argument("--port", type=int, default=DEFAULT_PORT)
    a = ap.parse_args()
    results = os.path.realpath(a.results)
    report = os.path.realpath(a.report or os.path.join(a.results, "report"))
    if not os.path.isfile(os.path.join(results, "results.json")):
        fail("%s: no results.json (not a result folder of `hybridlab run`)" % a.results, 2)
    if not os.path.isfile(os.path.join(report, "viewer.html")):
        fail("%s: no viewer.html (write the report first: hybridlab report %s%s)" % (
            a.report or os.path.join(a.results, "report"), a.results, " --out " + a.report if a.report else ""), 2)
    if not 0 <= a.port <= 65535:
        fail("--port %d: expected 0 (any free port) to 65535" % a.port, 2)
    root = os.path.commonpath([results, report])
    handler = functools.partial(type("Handler", (ResultSetHandler,), {"roots": (results, report)}), directory=root)
    try:
        server = http.server.ThreadingHTTPServer(("127.0.0.1", a.port), handler)
    except OSError as e:
        fail("cannot listen on 127.0.0.1:%d: %s" % (a.port, e.strerror), 3)
    base = "http://127.0.0.1:%d/" % server.server_address[1]
    page = urllib.parse.quote(os.path.relpath(report, root).replace(os.sep, "/")) + "/"
    print("serving %s on %s (Ctrl-C stops)" % (a.results, base))
    print("report: %s%sindex.html" % (base, page))
    print("viewer: %s%sviewer.html" % (base, page), flush=True)
    try:
        server.serve_forever()
    except KeyboardInterrupt:
        print("stopped")
    finally:
        server.server_close()


if __name__ == "__main__":
    main()
