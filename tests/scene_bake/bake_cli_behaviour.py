"""bake_cli_behaviour.py NANOBAKE SOURCE_DIR

How `nanobake bake` behaves around the work, on the small two-compartment scene of
hostile_scenes.py (it bakes in ~2-5 s):
- progress: one line per stage with its time when stderr is a pipe; a line updated in place
  (carriage return, percent) when stderr is a terminal (a pseudo-terminal here); nothing with --quiet;
- --dry-run: prints the estimate and the copy counts, writes no file;
- --max-memory below the estimate: refused before the heavy stages, naming the estimate and the
  limit, writing no file;
- SIGINT and SIGTERM during the bake: the process ends within a second by that signal, the
  package already at the output path is byte-identical afterwards, no other file appears.
"""
import os
import pty
import re
import select
import signal
import subprocess
import sys
import tempfile
import time

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import hostile_scenes  # noqa: E402  (the base scene)

STAGE_LINE = re.compile(r"^nanobake: ([a-z ]+)\.\.\. \d+\.\d s$")
PREVIOUS = b"the previous package, which an interrupted bake must leave alone\n"


def scene_in(folder, source):
    mesh = os.path.join(folder, "vesicle.obj")
    hostile_scenes.uv_sphere_obj(mesh)
    path = os.path.join(folder, "scene.json")
    hostile_scenes.write_scene(path, hostile_scenes.base_scene(os.path.join(source, "data", "structures"), mesh))
    return path


# Every bake here runs --no-cache: it must do the work whose progress, budget and interruption this
# tests (through the cache the second bake of the scene would end before the signal).
def run(args, **kw):
    return subprocess.run(args, capture_output=True, text=True, timeout=120, **kw)


def files_in(folder):
    return sorted(os.listdir(folder))


def check_lines(nanobake, scene, work, problems):
    out = os.path.join(work, "lines")
    os.mkdir(out)
    r = run([nanobake, "bake", scene, "--no-cache", "-o", os.path.join(out, "p.nup")])
    stages = [m.group(1) for m in map(STAGE_LINE.match, r.stderr.splitlines()) if m]
    print("piped stderr:", stages)
    for stage in ("molecules", "meshes", "tile sets", "shells", "core grids", "package content", "writing the package"):
        if stage not in stages:
            problems.append(f"piped: no line for stage '{stage}' in {r.stderr!r}")
    if r.returncode != 0:
        problems.append(f"piped: exit {r.returncode}: {r.stderr}")


def check_quiet(nanobake, scene, work, problems):
    out = os.path.join(work, "quiet")
    os.mkdir(out)
    r = run([nanobake, "bake", scene, "--no-cache", "-o", os.path.join(out, "p.nup"), "--quiet"])
    print("quiet stderr:", repr(r.stderr))
    if r.returncode != 0 or r.stderr:
        problems.append(f"--quiet: exit {r.returncode}, stderr {r.stderr!r}")


def check_terminal(nanobake, scene, work, problems):
    out = os.path.join(work, "terminal")
    os.mkdir(out)
    leader, follower = pty.openpty()
    p = subprocess.Popen([nanobake, "bake", scene, "--no-cache", "-o", os.path.join(out, "p.nup")], stdout=subprocess.DEVNULL,
                         stderr=follower)
    os.close(follower)
    seen = b""
    while True:
        ready, _, _ = select.select([leader], [], [], 120)
        if not ready:
            break
        try:
            chunk = os.read(leader, 65536)
        except OSError:  # the follower closed: the process ended
            break
        if not chunk:
            break
        seen += chunk
    os.close(leader)
    p.wait(timeout=120)
    text = seen.decode("utf-8", "replace")
    updates = text.count("\r")
    percents = re.findall(r"\d+%", text)
    print(f"terminal: {updates} in-place updates, percents {percents[:8]}...")
    if p.returncode != 0:
        problems.append(f"terminal: exit {p.returncode}: {text[-500:]}")
    if updates < 7 or not percents:
        problems.append(f"terminal: expected lines updated in place with a percent, got {text!r}")
    if re.search(r"^nanobake: [a-z ]+\.\.\. ", text, re.M):
        problems.append("terminal: piped-style lines on a terminal")


def check_dry_run(nanobake, scene, work, problems):
    out = os.path.join(work, "dry")
    os.mkdir(out)
    r = run([nanobake, "bake", scene, "--no-cache", "-o", os.path.join(out, "p.nup"), "--dry-run", "-q"])
    print("dry run:", r.stdout.strip().replace("\n", " | "))
    if r.returncode != 0 or not r.stdout.startswith("estimate:") or "virion:" not in r.stdout or "vesicle:" not in r.stdout:
        problems.append(f"--dry-run: exit {r.returncode}, stdout {r.stdout!r}, stderr {r.stderr!r}")
    if files_in(out):
        problems.append(f"--dry-run wrote {files_in(out)}")


def check_budget(nanobake, scene, work, problems):
    out = os.path.join(work, "budget")
    os.mkdir(out)
    r = run([nanobake, "bake", scene, "--no-cache", "-o", os.path.join(out, "p.nup"), "--max-memory", "1M", "-q"])
    print("budget:", r.stderr.strip().splitlines()[0] if r.stderr.strip() else "")
    if r.returncode != 1 or "more than the 1 MB allowed (--max-memory" not in r.stderr:
        problems.append(f"--max-memory 1M: exit {r.returncode}, stderr {r.stderr!r}")
    if files_in(out):
        problems.append(f"--max-memory refusal wrote {files_in(out)}")
    bad = run([nanobake, "bake", scene, "--no-cache", "-o", os.path.join(out, "p.nup"), "--max-memory", "lots"])
    if bad.returncode == 0 or "--max-memory" not in bad.stderr:
        problems.append(f"--max-memory lots: exit {bad.returncode}, stderr {bad.stderr!r}")


def check_interrupt(nanobake, scene, work, signal_number, after, problems):
    name = signal.Signals(signal_number).name
    out = os.path.join(work, f"interrupt-{name}-{after}")
    os.mkdir(out)
    package = os.path.join(out, "p.nup")
    with open(package, "wb") as f:
        f.write(PREVIOUS)
    p = subprocess.Popen([nanobake, "bake", scene, "--no-cache", "-o", package, "-q"], stdout=subprocess.DEVNULL,
                         stderr=subprocess.DEVNULL)
    time.sleep(after)
    if p.poll() is not None:
        problems.append(f"{name} at {after} s: the bake had already ended (exit {p.returncode}); nothing was tested")
        return
    sent = time.monotonic()
    p.send_signal(signal_number)
    try:
        p.wait(timeout=5)
    except subprocess.TimeoutExpired:
        p.kill()
        p.wait()
    took = time.monotonic() - sent
    print(f"{name} at {after:.1f} s: ended in {took:.3f} s with {p.returncode}, folder {files_in(out)}")
    if took > 1.0:
        problems.append(f"{name}: took {took:.2f} s to stop")
    if p.returncode != -signal_number:
        problems.append(f"{name}: ended with {p.returncode}, not by the signal")
    if files_in(out) != ["p.nup"] or open(package, "rb").read() != PREVIOUS:
        problems.append(f"{name}: the folder holds {files_in(out)} and the previous package changed")


def main():
    nanobake, source = os.path.abspath(sys.argv[1]), os.path.abspath(sys.argv[2])
    problems = []
    with tempfile.TemporaryDirectory(prefix="bake_cli_") as work:
        scene = scene_in(work, source)
        check_lines(nanobake, scene, work, problems)
        check_quiet(nanobake, scene, work, problems)
        check_terminal(nanobake, scene, work, problems)
        check_dry_run(nanobake, scene, work, problems)
        check_budget(nanobake, scene, work, problems)
        for signal_number in (signal.SIGINT, signal.SIGTERM):
            for after in (0.3, 1.5):
                check_interrupt(nanobake, scene, work, signal_number, after, problems)
    for p in problems:
        print("FAIL:", p)
    print("ok" if not problems else f"{len(problems)} problem(s)")
    return 1 if problems else 0


if __name__ == "__main__":
    sys.exit(main())
