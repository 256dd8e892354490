"""The README's shell commands, run: every block fenced ```sh is taken
command by command (backslash continuations joined) and run in a temporary
folder from the built tools, each must exit 0 and write what it names
(the path after -o, --out, --stats or --save-parts, oit.save_png's file,
and where --pick's stdout is sent; a folder must hold files; an oitstream command that names no
--out writes nothing, and fails). A block fenced
```sh notest: REASON is skipped, saying why (a display, big data, minutes);
a fence of build/bin commands that is neither fails the test, so no
command goes untested unsaid.

Small inputs stand in for the README's models, in the folder where the
commands run: MODEL alone is $OIT_README_MODEL (default MODEL.ply, 8 quads),
MODEL.ply/MODEL.oitp, model.off/model.ply and dragon.off are small scenes
made first, path.txt a two-view camera path, bench/ a folder as in the
repository; and, for time, every oitstream and oitbench render runs at
--size $OIT_README_SIZE (default 96x96, replacing the README's size or the
default), oitbench with --orbit 2 --frames 1, and --triangles 1000000
becomes --triangles $OIT_README_TRIANGLES (default 10000). `build` is the
build folder, `python` the package.

usage: test_readme.py README BUILD_DIR SOURCE_DIR [SCRATCH]"""
import os
import re
import shutil
import subprocess
import sys
import tempfile
import time


def blocks(text):
    """(first line number, info string, lines) of each fenced block."""
    out, cur = [], None
    for no, line in enumerate(text.splitlines(), 1):
        if line.startswith("```"):
            if cur is None:
                cur = (no, line[3:].strip(), [])
            else:
                out.append(cur)
                cur = None
        elif cur is not None:
            cur[2].append(line)
    return out


def commands(lines):
    """The block's commands: continuations joined, blank and comment-only
    lines (the README's notes under a command) dropped."""
    out, acc = [], ""
    for line in lines:
        if not acc and (not line.strip() or line.lstrip().startswith("#")):
            continue
        if line.rstrip().endswith("\\"):
            acc += line.rstrip()[:-1] + " "
            continue
        out.append(acc + line)
        acc = ""
    return out


def substitute(cmd):
    model = os.environ.get("OIT_README_MODEL", "MODEL.ply")
    size = os.environ.get("OIT_README_SIZE", "96x96")
    tris = os.environ.get("OIT_README_TRIANGLES", "10000")
    cmd = re.sub(r"\bMODEL\b(?!\.)", model, cmd)
    code, hash_, note = cmd.partition(" #")
    renders = re.search(r"build/bin/(oitstream|oitbench) ", code) and not re.search(
        r"oitbench plot|--compare|--window", code)
    if renders:
        code = re.sub(r"\s--size \S+", "", code).rstrip() + " --size " + size
    if renders and "build/bin/oitbench" in code:
        code = re.sub(r"\s--(orbit|frames) \S+", "", code) + " --orbit 2 --frames 1"
    return (code + hash_ + note).replace("--triangles 1000000", "--triangles " + tris)


def outputs(cmd):
    """What the command says it writes."""
    code = cmd.split(" #")[0]
    named = re.findall(r"(?:^|\s)(?:-o|--out|--stats|--save-parts)\s+(\S+)", code)
    named += re.findall(r'save_png\("([^"]+)"', code)
    # oitstream --pick prints JSON: the file its stdout is sent to
    if "--pick" in code:
        named += re.findall(r"(?:^|\s)>\s*(\S+)", code)
    # oitbench plot OUT RUN...: OUT gets the charts
    m = re.search(r"oitbench plot (\S+)", code)
    if m:
        named.append(m.group(1) + "/")
    return named


def make_inputs(work, bindir):
    def run(*args):
        subprocess.run(args, cwd=work, check=True, stdout=subprocess.DEVNULL,
                       stderr=subprocess.PIPE)
    run(bindir + "/oitgen", "quads", "--count", "8", "-o", "MODEL.ply")
    run(bindir + "/oitprep", "MODEL.ply", "-o", "MODEL.oitp")
    shutil.copy(os.path.join(work, "MODEL.ply"), os.path.join(work, "model.ply"))
    # a small closed mesh: an octahedron
    off = ("OFF\n6 8 0\n1 0 0\n-1 0 0\n0 1 0\n0 -1 0\n0 0 1\n0 0 -1\n"
           "3 0 2 4\n3 2 1 4\n3 1 3 4\n3 3 0 4\n3 2 0 5\n3 1 2 5\n3 3 1 5\n3 0 3 5\n")
    for name in ("model.off", "dragon.off"):
        with open(os.path.join(work, name), "w") as f:
            f.write(off)
    os.mkdir(os.path.join(work, "bench"))
    with open(os.path.join(work, "path.txt"), "w") as f:
        f.write("# two views of the quads\n0,0,4,0,0,0,0,1,0,45\n1,1,4,0,0,0,0,1,0,45\n")


def check_written(work, path):
    full = os.path.join(work, path)
    if os.path.isdir(full):
        return len(os.listdir(full)) > 0
    return not path.endswith("/") and os.path.isfile(full) and os.path.getsize(full) > 0


def main():
    readme, build, src = (os.path.abspath(a) for a in sys.argv[1:4])
    scratch = sys.argv[4] if len(sys.argv) > 4 else None
    # A sanitized build's liboit.so needs the sanitizer runtime preloaded
    # into the Python that loads it (as python_oit does); its leak checking
    # stays off there (the interpreter's own allocations read as leaks).
    preload = sys.argv[5] if len(sys.argv) > 5 else ""
    bindir = os.path.join(build, "bin")
    text = open(readme).read()
    work = tempfile.mkdtemp(prefix="readme.", dir=scratch)
    os.symlink(build, os.path.join(work, "build"))
    os.symlink(os.path.join(src, "python"), os.path.join(work, "python"))
    make_inputs(work, bindir)
    env = dict(os.environ, PYTHONDONTWRITEBYTECODE="1")
    env.pop("LD_PRELOAD", None)
    fails, ran, start = 0, 0, time.time()
    for no, info, lines in blocks(text):
        tools = any("build/bin/" in l for l in lines)
        if not info.startswith("sh"):
            if tools and not info.startswith("$"):
                print(f"FAIL: README.md:{no}: build/bin commands in a ```{info} block: fence "
                      "it ```sh (run here) or ```sh notest: REASON")
                fails += 1
            continue
        if info.startswith("sh notest"):
            reason = info.partition(":")[2].strip()
            if not reason:
                print(f"FAIL: README.md:{no}: ```sh notest without a reason")
                fails += 1
            else:
                print(f"skip README.md:{no}: {reason}")
            continue
        for cmd in commands(lines):
            run = substitute(cmd)
            if "/usr/bin/python3" in run and subprocess.run(
                    ["/usr/bin/python3", "-c", "import numpy"],
                    capture_output=True).returncode != 0:
                print(f"skip README.md:{no}: /usr/bin/python3 has no numpy: {cmd}")
                continue
            t0 = time.time()
            cenv = env
            if preload and "python3" in run:
                cenv = dict(env, LD_PRELOAD=preload, ASAN_OPTIONS="detect_leaks=0")
            p = subprocess.run(["sh", "-c", run], cwd=work, env=cenv, capture_output=True,
                               text=True)
            ran += 1
            missing = [o for o in outputs(run) if not check_written(work, o)]
            if "build/bin/oitstream " in run and not outputs(run):
                missing = ["anything: an oitstream render without --out writes no image"]
            verdict = "ok" if p.returncode == 0 and not missing else "FAIL"
            print(f"{verdict} README.md:{no}: {run.split(' #')[0].strip()} "
                  f"({time.time() - t0:.1f} s)")
            if p.returncode != 0:
                fails += 1
                print(f"  exit {p.returncode}: {(p.stderr or p.stdout).strip()[-600:]}")
            elif missing:
                fails += 1
                print(f"  did not write {', '.join(missing)}")
    print(f"README: {ran} commands run, {fails} failure(s), {time.time() - start:.1f} s")
    if ran == 0:
        print("FAIL: no ```sh block ran")
        fails += 1
    if fails == 0:
        shutil.rmtree(work)
    else:
        print(f"their files: {work}")
    return 1 if fails else 0


if __name__ == "__main__":
    sys.exit(main())
