"""What the eval label's test scripts share: the checks that failed, the exit without an OpenGL context, the end.

    from script_checks import check, finish, no_gl
"""
import os

SKIP = 77  # CTest's SKIP_RETURN_CODE for these tests
failures = []


def check(condition, what):
    """Records `what` as failed unless `condition` holds; the script goes on to its other checks."""
    if not condition:
        failures.append(what)


def no_gl(why):
    """The exit status without an OpenGL context: a skip, or a failure under EMCV_REQUIRE_GL=1 (CI)."""
    if os.environ.get("EMCV_REQUIRE_GL") == "1":
        print("EMCV_REQUIRE_GL=1 but there is no OpenGL context: " + why)
        return 1
    print("skipped: no OpenGL context (set EMCV_REQUIRE_GL=1 to make this a failure): " + why)
    return SKIP


def finish(name):
    """Prints every failed check and returns the script's exit status."""
    for f in failures:
        print("FAILED: " + f)
    print(f"{name}: {len(failures)} failure(s)")
    return 1 if failures else 0
