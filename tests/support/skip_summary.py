#!/usr/bin/python3
"""The last line of `ctest`'s output: how many tests were skipped and why.

ctest lists skipped tests by name only; their reasons are in each test's output, which
Testing/Temporary/LastTest.log keeps (LastTest.log.tmp while ctest runs). ctest runs this after the tests (CTEST_CUSTOM_POST_TEST in
the build folder's CTestCustom.cmake) and prints what it prints, e.g.

    2 skipped: no Vulkan device (Raster/GBuffer..., ...); playwright-core is missing (ViewerInBrowser)

A skip is GoogleTest's: a "Skipped" line, the reason, then "[  SKIPPED ]" (the browser test prints
the same). Never fails: a summary that cannot be made is left out.
    skip_summary.py BUILD_DIR"""
import collections
import pathlib
import re
import sys


def skipped_tests(log_text):
    """(test name, reason) for every skipped test in a LastTest.log."""
    out = []
    for block in re.split(r'\n(?=\d+/\d+ Testing: )', log_text):
        name = re.match(r'\d+/\d+ Testing: (.*)', block)
        body = block.split('Output:\n', 1)[-1].split('<end of output>', 1)[0]
        if not name or '[  SKIPPED ]' not in body:
            continue
        reason = re.search(r'(?:^|\n)[^\n]*\bSkipped\n(.*?)\n\[  SKIPPED \]', body, re.S)
        text = ' '.join(reason.group(1).split()) if reason else ''
        out.append((name.group(1).strip(), text or 'no reason given'))
    return out


def summary(skipped):
    if not skipped:
        return ''
    by_reason = collections.OrderedDict()
    for name, reason in skipped:
        by_reason.setdefault(reason, []).append(name)
    parts = []
    for reason, names in by_reason.items():
        shown = ', '.join(names[:3]) + (f', ... {len(names) - 3} more' if len(names) > 3 else '')
        parts.append(f'{reason} ({shown})')
    return f'{len(skipped)} skipped: ' + '; '.join(parts)


def main():
    try:
        # While the post-test command runs, ctest is still writing the log under its .tmp name.
        log = pathlib.Path(sys.argv[1]) / 'Testing' / 'Temporary' / 'LastTest.log'
        if log.with_suffix('.log.tmp').exists():
            log = log.with_suffix('.log.tmp')
        with open(log, encoding='utf-8', errors='replace') as f:
            line = summary(skipped_tests(f.read()))
        if line:
            print(line)
    except Exception:  # noqa: BLE001 - a missing summary must never fail the test command
        pass
    return 0


if __name__ == '__main__':
    sys.exit(main())
