#!/usr/bin/python3
"""scripts/eval/run_eval.py's job list, shards and determinism, with the built renderer:
  - the job list is stable (two listings agree) and indexed 0..n-1 in order;
  - --shard I/N splits it: the shards are disjoint, their union is the whole list, shard I holds index % N == I;
  - bad --jobs / --shard values are refused with a message naming the option;
  - --merge over a raw folder that lacks jobs refuses and names them;
  - a run of some stages records itself under a name of its own (the record of the run that made the other
    stages' raw files stays, for the context block), and a later run of every stage removes those records; a
    --resume run adds its line after the record of the run that made the other raw files;
  - --check-determinism: the --quick quality jobs run with --jobs 1 and with --jobs 2 into two raw folders give
    byte-identical quality tables (PSNR raw and resolved, samples, lag).

    /usr/bin/python3 tests/eval/test_eval_jobs.py BUILD_DIR   (BUILD_DIR/bin holds emcv-demo and emcv-eval)

Exit 77 (CTest's SKIP_RETURN_CODE here) when the renderer finds no OpenGL context, unless EMCV_REQUIRE_GL=1.
"""
import os
import subprocess
import sys
import tempfile

ROOT = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
SCRIPT = os.path.join(ROOT, "scripts", "eval", "run_eval.py")
sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from script_checks import check, finish, no_gl  # noqa: E402


def run_eval(*args):
    return subprocess.run(["/usr/bin/python3", SCRIPT, *args], capture_output=True, text=True)


def listing(build, *args):
    r = run_eval("--build", build, "--list", *args)
    check(r.returncode == 0, f"--list {' '.join(args)} exits 0 (got {r.returncode}: {r.stderr.strip()})")
    return [line.split("\t") for line in r.stdout.splitlines()]


def check_run_records():
    sys.path.insert(0, os.path.dirname(SCRIPT))
    import run_eval
    every = run_eval.QUALITY_STAGES + run_eval.TIMING_STAGES
    with tempfile.TemporaryDirectory() as raw:
        full = run_eval.run_file_name("all", every, raw, False)
        timing = run_eval.run_file_name("all", run_eval.TIMING_STAGES, raw, False)
        check(full != timing, f"a timing-only run's record ({timing}) does not replace the full run's ({full})")
        for name in (full, timing):
            open(os.path.join(raw, name), "w").close()
        check(run_eval.run_file_name("all", list(reversed(every)), raw, True) == full and
              os.path.exists(os.path.join(raw, timing)), "a --resume run of every stage keeps the stage records")
        run_eval.run_file_name("all", every, raw, False)
        check(not os.path.exists(os.path.join(raw, timing)), "a run of every stage removes the stage records")
    with tempfile.TemporaryDirectory() as raw:
        run_eval.write_run_record(raw, "all", every, False, "first run")
        run_eval.write_run_record(raw, "all", every, True, "resumed run")
        runs = run_eval.provenance([], raw)[2]
        check(runs == ["first run", "resumed run"],
              f"a --resume run's record follows the record of the run that made the other raw files (got {runs})")
        run_eval.write_run_record(raw, "all", every, False, "new run")
        runs = run_eval.provenance([], raw)[2]
        check(runs == ["new run"], f"a run that is not resumed replaces the record (got {runs})")


def main(build):
    check_run_records()
    full = listing(build)
    check(len(full) > 20, f"the full job list has more than 20 jobs (got {len(full)})")
    check(full == listing(build), "two listings of the job list agree")
    check([int(row[0]) for row in full] == list(range(len(full))), "job indices run 0..n-1 in order")
    kinds = [row[2] for row in full]
    check("timing" in kinds and kinds.index("timing") == len(kinds) - kinds[::-1].count("timing"),
          "the timing jobs come last")

    shards = [listing(build, "--shard", f"{i}/3") for i in range(3)]
    union = sorted((row for s in shards for row in s), key=lambda row: int(row[0]))
    check(union == full, "shards 0/3, 1/3 and 2/3 together are the whole list, each job once")
    for i, s in enumerate(shards):
        check(all(int(row[0]) % 3 == i for row in s), f"shard {i}/3 holds the jobs with index % 3 == {i}")

    for args, needle in ((["--jobs", "0"], "--jobs"), (["--jobs", "two"], "--jobs"), (["--shard", "3/2"], "--shard"),
                         (["--shard", "1"], "--shard"), (["--shard", "-1/2"], "--shard")):
        r = run_eval("--build", build, "--list", *args)
        check(r.returncode != 0 and needle in r.stderr, f"{' '.join(args)} is refused naming {needle} "
                                                        f"(got {r.returncode}: {r.stderr.strip()})")

    with tempfile.TemporaryDirectory() as tmp:
        r = run_eval("--build", build, "--quick", "--merge", "--raw-dir", tmp, "--stages", "quality")
        check(r.returncode != 0 and "cannot merge" in r.stderr and "quality/light-off-B8-s1" in r.stderr,
              f"--merge over an empty raw folder refuses and names the missing jobs (got {r.stderr.strip()[:300]})")

    r = run_eval("--build", build, "--check-determinism")
    if r.returncode != 0 and "no OpenGL context" in r.stderr:
        return no_gl(r.stderr.strip())
    print(r.stdout[-2000:])
    check(r.returncode == 0 and "byte-identical" in r.stdout,
          f"--check-determinism passes (got {r.returncode}: {r.stderr.strip()[-1500:]})")

    return finish("test_eval_jobs")


if __name__ == "__main__":
    if len(sys.argv) != 2:
        sys.exit(__doc__)
    sys.exit(main(sys.argv[1]))
