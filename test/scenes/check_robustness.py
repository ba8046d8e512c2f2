#!/usr/bin/env python3
# SPDX-License-Identifier: Apache-2.0
"""The scene runner against a hostile environment (issue 13): a full disk, a file size
limit, symbolic links planted in the results directory, a standard output that cannot
be written (a full device, a closed pipe), and scene files that are not scene files (a directory, a device without
end, a file of 100 MB, an empty file, a path with escape sequences); a user's own files
in the results directory, and a log.txt planted there as a link or a FIFO.

Usage: check_robustness.py PROGRAM WORKDIR CASE     (one case; exit 0 if it passes)
       check_robustness.py PROGRAM WORKDIR --all    (every case)
       check_robustness.py --list                   (the names of the cases)

A case whose mechanism this machine lacks prints "skipped: <why>" and exits 0 (CTest
marks it skipped by that text): `full-disk` needs root and a tmpfs mount (CI runs as
root on Debian 12; a container without CAP_SYS_ADMIN cannot mount). The file size
limit (RLIMIT_FSIZE: the program ignores SIGXFSZ, so that write() fails with EFBIG)
needs no privilege and exercises the same checks, so a failed write is tested
everywhere.
"""

import os
import resource
import shutil
import signal
import subprocess
import sys

HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.dirname(os.path.dirname(HERE))
#: A scene whose files together need more than 64 KB (histories.csv alone ~60 KB)
BIG_SCENE = os.path.join(ROOT, "example", "scenes", "two_steel_balls.nml")
RESULT_FILES = ("summary.csv", "histories.csv", "phase.csv", "parameters.csv", "scene.nml", "log.txt")


class Failed(Exception):
    pass


def run(program, args, timeout=120, **kwargs):
    return subprocess.run([program] + args, capture_output=True, timeout=timeout, **kwargs)


def expect(condition, what, result=None):
    if not condition:
        detail = ""
        if result is not None:
            detail = (f"\nexit code {result.returncode}\nstdout: {result.stdout.decode(errors='replace')[-2000:]}"
                      f"\nstderr: {result.stderr.decode(errors='replace')[-2000:]}")
        raise Failed(what + detail)


def fresh(work, name):
    path = os.path.join(work, name)
    if os.path.ismount(path):
        # left mounted by an interrupted run of the full-disk case
        subprocess.run(["umount", path], capture_output=True)
    if os.path.lexists(path):
        if os.path.isdir(path) and not os.path.islink(path):
            shutil.rmtree(path)
        else:
            os.remove(path)
    os.makedirs(path)
    return path


def leftovers(directory):
    """Every path below directory (empty if it does not exist)."""
    found = []
    for top, dirs, files in os.walk(directory):
        found += [os.path.join(top, n) for n in dirs + files]
    return found


def expect_failed_write(result, results_dir, parent):
    """A run that could not write its files: exit 1, the message names a file of the
    results directory and says the write failed, and nothing is left in `parent`."""
    err = result.stderr.decode(errors="replace")
    expect(result.returncode == 1, "the run must fail with exit code 1", result)
    expect(results_dir in err and "writing failed" in err,
           "the message must name the file that could not be written", result)
    left = leftovers(parent)
    expect(not left, f"the failed run left files behind: {left}", result)


# ---------------------------------------------------------------------------
# The cases
# ---------------------------------------------------------------------------


def case_full_disk(program, work):
    """Results on a 64 KB tmpfs: the run fails, names the file, leaves nothing."""
    if os.geteuid() != 0:
        return "skipped: a tmpfs mount needs root (the file size limit case covers the checks)"
    mount = fresh(work, "full-disk")
    r = subprocess.run(["mount", "-t", "tmpfs", "-o", "size=64k", "tmpfs", mount], capture_output=True)
    if r.returncode != 0:
        return ("skipped: cannot mount a tmpfs here (" + r.stderr.decode(errors="replace").strip()
                + "); the file size limit case covers the checks")
    try:
        target = os.path.join(mount, "par", "out")
        result = run(program, [BIG_SCENE, "-o", target])
        expect_failed_write(result, target, mount)
    finally:
        subprocess.run(["umount", mount], capture_output=True)
    return None


def limited(limit):
    """A file size limit for the child (SIGXFSZ left at its default, which kills: the
    program must ignore it itself)."""
    def start():
        signal.signal(signal.SIGXFSZ, signal.SIG_DFL)
        resource.setrlimit(resource.RLIMIT_FSIZE, (limit, limit))
    return start


def case_file_size_limit(program, work):
    """A file size limit of 40 KB: histories.csv cannot be written whole. The run fails
    and names the file; an earlier run's results in the same directory stay as they
    were; a new directory (and its new parents) is removed."""
    base = fresh(work, "file-size-limit")
    target = os.path.join(base, "new", "out")
    result = run(program, [BIG_SCENE, "-o", target], preexec_fn=limited(40000))
    expect_failed_write(result, target, base)
    expect(b"File too large" in result.stderr, "the message must give the reason", result)
    # an earlier run's complete results survive a failed run
    done = os.path.join(base, "kept")
    result = run(program, [BIG_SCENE, "-o", done])
    expect(result.returncode == 0, "the unlimited run must succeed", result)
    before = {n: open(os.path.join(done, n), "rb").read() for n in os.listdir(done)}
    result = run(program, [BIG_SCENE, "-o", done], preexec_fn=limited(40000))
    err = result.stderr.decode(errors="replace")
    expect(result.returncode == 1 and "writing failed" in err, "the limited run must fail", result)
    after = {n: open(os.path.join(done, n), "rb").read() for n in os.listdir(done)}
    expect(after == before, "the failed run changed the earlier results: "
           + ", ".join(sorted(set(after) ^ set(before)) or [n for n in after if after[n] != before.get(n)]))
    return None


def case_symlink_partial(program, work):
    """A symbolic link planted at out/summary.csv.partial is not followed: its target
    keeps its content, and summary.csv is a regular file of this run."""
    base = fresh(work, "symlink-partial")
    out = os.path.join(base, "out")
    os.makedirs(out)
    victim = os.path.join(base, "victim.txt")
    with open(victim, "w") as fh:
        fh.write("precious\n")
    os.symlink(victim, os.path.join(out, "summary.csv.partial"))
    os.symlink(victim, os.path.join(out, "parameters.csv"))
    result = run(program, ["-o", out])
    expect(result.returncode == 0, "the run must succeed", result)
    expect(open(victim).read() == "precious\n", "the target of the planted link was overwritten")
    for name in ("summary.csv", "parameters.csv"):
        path = os.path.join(out, name)
        expect(not os.path.islink(path) and os.path.isfile(path), f"{name} must be a regular file")
    expect(open(os.path.join(out, "summary.csv")).readline().startswith("speed [m/s],"),
           "summary.csv is not this run's table")
    expect(not [n for n in os.listdir(out) if n.endswith(".partial")], "a .partial file was left")
    return None


def case_parents_removed(program, work):
    """A run that fails after creating -o par/a/b/c removes the directories it made."""
    base = fresh(work, "parents-removed")
    scene = os.path.join(base, "fails.nml")
    with open(scene, "w") as fh:
        fh.write("&scene speeds = 1e-300 /\n&body1 mass = 0.1 /\n&contact stiffness = 1e10 /\n"
                 "&damping b = 0.1 /\n")
    result = run(program, [scene, "-o", os.path.join(base, "par", "a", "b", "c")])
    expect(result.returncode == 1, "the scene's impact must fail", result)
    expect(not os.path.exists(os.path.join(base, "par")), "par/ was left behind: "
           + ", ".join(leftovers(os.path.join(base, "par"))))
    return None


def case_standard_output_full(program, work):
    """The tables cannot be written (standard output on /dev/full): exit 1, the
    message says so, no results are left. --help and --version likewise."""
    if not os.path.exists("/dev/full"):
        return "skipped: no /dev/full"
    base = fresh(work, "standard-output-full")
    out = os.path.join(base, "out")
    with open("/dev/full", "w") as full:
        result = subprocess.run([program, "-o", out], stdout=full, stderr=subprocess.PIPE, timeout=120)
        expect(result.returncode == 1, f"exit code {result.returncode}, expected 1 "
               + result.stderr.decode(errors="replace"))
        expect(b"the standard output" in result.stderr, "the message must name the standard output")
        expect(not os.path.exists(out), "the results of a run whose tables were lost were left")
        for option in ("--help", "--version", "--show-default", "--plan"):
            result = subprocess.run([program, option], stdout=full, stderr=subprocess.PIPE, timeout=60)
            expect(result.returncode == 1, f"{option} > /dev/full: exit code {result.returncode}")
    return None


def case_closed_pipe(program, work):
    """The standard output is a pipe whose reader has gone (hcimpact | head -1, after
    head has ended): exit 1 ("Broken pipe"), not death by SIGPIPE halfway with the
    .partial files and new directories left behind."""
    base = fresh(work, "closed-pipe")
    out = os.path.join(base, "par", "out")
    reader, writer = os.pipe()
    os.close(reader)
    try:
        # subprocess restores SIGPIPE to its default in the child: the program must
        # ignore it itself
        result = subprocess.run([program, "-o", out], stdout=writer, stderr=subprocess.PIPE,
                                timeout=120)
    finally:
        os.close(writer)
    expect(result.returncode == 1, f"exit code {result.returncode}, expected 1 "
           + result.stderr.decode(errors="replace"))
    expect(b"Broken pipe" in result.stderr, "the message must give the reason: "
           + result.stderr.decode(errors="replace"))
    expect(not os.path.exists(os.path.join(base, "par")), "the results were left behind")
    return None


def scene_refused(program, path, message, timeout=120):
    result = run(program, [path, "--no-files"], timeout=timeout)
    err = result.stderr.decode(errors="replace")
    expect(result.returncode == 2, f"{path!r} must be refused with exit code 2", result)
    expect(message in err, f"the message must say: {message}", result)
    return err


def case_directory_as_scene(program, work):
    base = fresh(work, "directory-as-scene")
    scene_refused(program, base, base + ": is a directory, not a scene file")
    return None


def case_endless_input(program, work):
    """/dev/zero as the scene: refused at once (not text), not read for ever."""
    if not os.path.exists("/dev/zero"):
        return "skipped: no /dev/zero"
    scene_refused(program, "/dev/zero", "/dev/zero:1: character 1 is not text (byte 0x00)", timeout=20)
    return None


def case_huge_scene(program, work):
    """A scene of 100 MB (a valid scene, then comment lines): refused after 10000 lines."""
    base = fresh(work, "huge-scene")
    path = os.path.join(base, "huge.nml")
    head = ("&scene speeds = 1 /\n&body1 mass = 0.1 /\n&contact stiffness = 1e10 /\n"
            "&damping b = 0.1 /\n")
    line = "! " + "x" * 97 + "\n"
    with open(path, "w") as fh:
        fh.write(head)
        block = line * 10000
        for _ in range(100 * 1024 * 1024 // len(block) + 1):
            fh.write(block)
    try:
        scene_refused(program, path, path + ": more than 10000 lines", timeout=60)
    finally:
        os.remove(path)
    return None


def case_empty_scene(program, work):
    base = fresh(work, "empty-scene")
    path = os.path.join(base, "empty.nml")
    open(path, "w").close()
    scene_refused(program, path, path + ": the scene file is empty")
    return None


def case_escape_in_path(program, work):
    """A path with escape sequences is quoted with them shown as '?', not sent to the
    terminal: in an error message, and in the log and the default results directory
    of a scene that runs."""
    base = fresh(work, "escape-in-path")
    path = os.path.join(base, "\x1b]0;title\x07.nml")
    err = scene_refused(program, path, os.path.join(base, "?]0;title?.nml: no such scene file"))
    expect("\x1b" not in err and "\x07" not in err, "control characters reached the terminal")
    with open(path, "w") as fh:
        fh.write("&scene speeds = 1 /\n&body1 mass = 0.1 /\n&contact stiffness = 1e10 /\n"
                 "&damping b = 0.1 /\n")
    result = run(program, [path], cwd=base)
    expect(result.returncode == 0, "the scene must run", result)
    expect(b"\x1b" not in result.stdout + result.stderr and b"\x07" not in result.stdout + result.stderr,
           "control characters reached the terminal", result)
    expect(os.path.isdir(os.path.join(base, "hcimpact-results", "?]0;title?")),
           "the default results directory must be named with '?' for the control characters", result)
    return None


def case_own_files_kept(program, work):
    """A directory of the user's given with -o: their files that bear names the runner
    writes but that this run does not write (motion.csv, phase.csv) are kept, as are
    their other files; the log's last line lists this run's files. The earlier run's
    files that a later run does not write are removed (no mixture of two runs), the
    user's own files among them kept."""
    base = fresh(work, "own-files-kept")
    out = os.path.join(base, "mine")
    os.makedirs(out)
    own = {"motion.csv": "my motion\n", "phase.csv": "my phase\n", "notes.txt": "notes\n"}
    for name, text in own.items():
        with open(os.path.join(out, name), "w") as fh:
            fh.write(text)
    result = run(program, ["-q", "-o", out])
    expect(result.returncode == 0, "the run must succeed", result)
    for name, text in own.items():
        path = os.path.join(out, name)
        expect(os.path.isfile(path) and open(path).read() == text,
               f"the user's {name} was removed or changed by a run that does not write it")
    lines = open(os.path.join(out, "log.txt")).read().splitlines()
    expect(lines[-1] == "Files of this run: parameters.csv summary.csv scene.nml log.txt",
           f"the log's last line must list the run's files: {lines[-1]!r}")
    # the earlier run's files (histories.csv, phase.csv) go when the next run does not
    # write them; a file the user added in between stays
    done = os.path.join(base, "results")
    result = run(program, [BIG_SCENE, "-q", "-o", done])
    expect(result.returncode == 0, "the first run must succeed", result)
    first = set(os.listdir(done))
    expect({"histories.csv", "phase.csv"} <= first, f"the first run's files: {sorted(first)}")
    with open(os.path.join(done, "motion.csv"), "w") as fh:
        fh.write("my motion\n")
    result = run(program, ["-q", "-o", done])
    expect(result.returncode == 0, "the second run must succeed", result)
    after = sorted(os.listdir(done))
    expect(after == ["log.txt", "motion.csv", "parameters.csv", "scene.nml", "summary.csv"],
           f"after the second run: {after}")
    return None


def case_planted_log(program, work):
    """log.txt planted as a symbolic link to a file that lists motion.csv as a file of
    the earlier run, or as a FIFO: the link is not followed, the FIFO not read (the run
    does not wait on it), the user's motion.csv is kept, the link's target unchanged,
    and log.txt becomes this run's regular file."""
    base = fresh(work, "planted-log")
    decoy = os.path.join(base, "decoy.txt")
    with open(decoy, "w") as fh:
        fh.write("Files of this run: motion.csv summary.csv log.txt\n")
    for kind in ("link", "fifo"):
        out = os.path.join(base, kind)
        os.makedirs(out)
        with open(os.path.join(out, "motion.csv"), "w") as fh:
            fh.write("my motion\n")
        log = os.path.join(out, "log.txt")
        if kind == "link":
            os.symlink(decoy, log)
        else:
            os.mkfifo(log)
        result = run(program, ["-q", "-o", out], timeout=60)
        expect(result.returncode == 0, f"the run must succeed with log.txt a {kind}", result)
        expect(os.path.isfile(os.path.join(out, "motion.csv")),
               f"log.txt a {kind}: the user's motion.csv was removed")
        expect(os.path.isfile(log) and not os.path.islink(log),
               f"log.txt a {kind}: log.txt must be this run's regular file")
    expect(open(decoy).read() == "Files of this run: motion.csv summary.csv log.txt\n",
           "the target of the planted link was changed")
    return None


CASES = {
    "full-disk": case_full_disk,
    "file-size-limit": case_file_size_limit,
    "symlink-partial": case_symlink_partial,
    "parents-removed": case_parents_removed,
    "standard-output-full": case_standard_output_full,
    "closed-pipe": case_closed_pipe,
    "directory-as-scene": case_directory_as_scene,
    "endless-input": case_endless_input,
    "huge-scene": case_huge_scene,
    "empty-scene": case_empty_scene,
    "escape-in-path": case_escape_in_path,
    "own-files-kept": case_own_files_kept,
    "planted-log": case_planted_log,
}


def main(argv):
    if argv[1:] == ["--list"]:
        print(";".join(CASES))
        return 0
    if len(argv) != 4:
        print(__doc__, file=sys.stderr)
        return 2
    program, work, which = os.path.abspath(argv[1]), os.path.abspath(argv[2]), argv[3]
    names = list(CASES) if which == "--all" else [which]
    os.makedirs(work, exist_ok=True)
    failed = 0
    for name in names:
        if name not in CASES:
            print(f"unknown case {name} (cases: {', '.join(CASES)})", file=sys.stderr)
            return 2
        try:
            note = CASES[name](program, work)
            print(f"{name}: {note}" if note else f"{name}: passed")
        except (Failed, subprocess.TimeoutExpired) as problem:
            print(f"{name}: FAILED: {problem}")
            failed += 1
    return 1 if failed else 0


if __name__ == "__main__":
    sys.exit(main(sys.argv))
