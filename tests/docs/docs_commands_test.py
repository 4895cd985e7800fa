#!/usr/bin/env python3
"""docs_commands_test.py — every `seasim` command shown in README.md and docs/*.md runs (ctest docs.commands).

    tests/docs/docs_commands_test.py SEASIM_BINARY REPO_DIR [WORK_DIR]

Extracts the fenced shell blocks' lines that start with `seasim` or `build/seasim` (continuation lines
joined, comments dropped) and runs each in an empty work folder at a small size, failing on a non-zero
exit, so the docs cannot go stale against the command line. Each command is run as written except:
  * the binary is SEASIM_BINARY; scenes/, jobs/, tests/ paths are the repository's; outputs (-o, --csv,
    --plot, ref.exr ...) stay relative, in the work folder, and an absolute -o moves into it;
  * `[...]` (optional arguments in a synopsis) is dropped;
  * a command that takes --set gets --set camera.width=32 --set camera.height=18 (`bench --frames`
    and `ocean` also a 64-point FFT grid), `run` and `farm` get -o in the work folder, sizes and counts
    are cut (--steps 16, --frames 2, --sizes 32,64, --wavelengths 3,8, --repeat 1); `run` and `farm`
    without -o write to job_out/<job file's stem>, so a tutorial's shards, status and merge meet;
  * `cache clear` runs against private, empty cache folders (it would empty the build's);
  * the blocks' shell lines that make files (mkdir, cp, sed ... > file) run too, in order, in the work
    folder, where scenes/, jobs/, docs/, data/ and tests/ link to the repository's;
  * a file a block writes with a here-document (`cat > my_scene.toml <<'EOF'` ... `EOF`) is written
    into the work folder first, so a tutorial's commands on its own scene run too.
A line with a placeholder (an all-capitals word such as JOB, N, DIR) is a synopsis, not a command:
it is listed and not run. EXCLUDED below lists the commands that cannot run here, with the reason.
"""
import os
import re
import shlex
import shutil
import subprocess
import sys
import tempfile
import time
from pathlib import Path

# (pattern in the command, reason): commands this test cannot run on a build machine.
EXCLUDED = [
    (r"\bpreview\b", "opens a window (GLFW, needs a display); tests/integration/preview_cli_test.cpp covers it"),
    (r"--submit\b", "submits to Slurm: needs a configured cluster (root for slurmd); ctest farm.slurm covers it"),
    (r"\bfarm merge jobs/jerlov_table", "README writes the farm's scripts only: no shard renders its 30 items here"),
    (r"render out/view_1\.toml", "renders the file the preview window's S key saved"),
    (r"--device[ =](gpu|nvidia|amd)", "needs a GPU and its vendor's OpenCL driver (docs/gpu.md); CI has PoCL only"),
    (r"--devices?[ =]\S*intel", "needs Intel's OpenCL runtime (make intel-opencl); runtimes.intel_vs_pocl_scenes covers it"),
    (r"\blocal-cluster (start|stop)\b", "starts or stops Slurm daemons: needs root; ctest farm.slurm runs the same script"),
]
# Shell lines in the blocks that make files the next commands read (mkdir, cp, sed > file ...): run
# with bash in the work folder, where scenes/, jobs/, docs/, data/ and tests/ link to the repository's.
# A line with an absolute path (or sudo) is never run: the test writes only inside its work folder.
PREPARE = re.compile(r"^(\$ )?(mkdir|cp|sed|touch) ")
OUTSIDE = re.compile(r"(^|[\s>=])(/|~)|\bsudo\b")
# (pattern, reason): commands the docs show failing on purpose; they must exit non-zero.
EXPECTED_TO_FAIL = [
    (r"validate mywork/typo\.toml", "the tutorial shows validate's message for a misspelt key"),
]
PLACEHOLDER = re.compile(r"^[A-Z][A-Z0-9_]*(\.[a-z]+)?$")  # JOB, N, DIR, REF.exr; not IB or 3C (water types)
TIMEOUT_S = 150  # one command
SMALL = ["--set", "camera.width=32", "--set", "camera.height=18"]
TAKES_SET = {"render", "run", "reference", "sweep", "bench", "plan", "ocean", "underwater-study", "seashore-study"}


def doc_files(repo):
    files = [repo / "README.md"] + sorted((repo / "docs").glob("*.md"))
    return [f for f in files if f.is_file()]


def commands(path, files):
    """(line number, command text) of each seasim command in the file's fenced blocks, in order; the
    here-documents the blocks write are added to `files` (name -> text)."""
    out, in_block, pending, start = [], False, "", 0
    heredoc, heredoc_end, heredoc_lines = None, None, []
    for number, line in enumerate(path.read_text(encoding="utf-8").splitlines(), 1):
        stripped = line.strip()
        if heredoc is not None:
            if stripped == heredoc_end:
                files[heredoc] = "\n".join(heredoc_lines) + "\n"
                heredoc = None
            else:
                heredoc_lines.append(line)
            continue
        if stripped.startswith("```"):
            in_block, pending = not in_block, ""
            continue
        if not in_block:
            continue
        m = re.match(r"^(\$ )?cat > ?(\S+) <<-?'?\"?(\w+)'?\"?$", stripped)
        if m:
            heredoc, heredoc_end, heredoc_lines = m.group(2), m.group(3), []
            continue
        if not pending and PREPARE.match(stripped) and not OUTSIDE.search(stripped):
            out.append((number, "!" + stripped.removeprefix("$ ")))  # a shell line that makes a file
            continue
        if pending:
            pending += " " + stripped
        elif re.match(r"^(\$ )?(build/)?seasim( |$)", stripped):
            pending, start = stripped.removeprefix("$ "), number
        else:
            continue
        if pending.endswith("\\"):
            pending = pending[:-1]
            continue
        out.append((start, pending))
        pending = ""
    return out


def rewrite(words, binary, repo, work):
    words = [w for w in words]
    words[0] = binary
    sub = words[1] if len(words) > 1 else ""
    result = []
    for w in words:
        for prefix in ("scenes/", "jobs/", "tests/"):
            if w.startswith(prefix) and (repo / w).exists():
                w = str(repo / w)
        result.append(w)
    words = result

    def cut(option, value):
        if option in words:
            i = words.index(option)
            if i + 1 < len(words):
                words[i + 1] = value

    cut("--steps", "16")
    cut("--frames", "2")
    cut("--sizes", "32,64")
    cut("--wavelengths", "3,8")
    cut("--repeat", "1")
    if sub == "bench" and "--repeat" not in words:
        words += ["--repeat", "1"]
    if sub in TAKES_SET and not (sub == "ocean" and "--bench" in words):
        words += SMALL
    if sub == "ocean" or (sub == "bench" and "--frames" in words):
        if "--bench" not in words:
            words += ["--set", "surface.grid=64"]
    # An absolute output folder in a doc (-o /tmp/seasim-farm) moves into the work folder too.
    for option in ("-o", "--out", "--output-dir"):
        if option in words[:-1]:
            i = words.index(option) + 1
            if os.path.isabs(words[i]) and not words[i].startswith(str(work)):
                words[i] = str(work / Path(words[i]).name)
    if sub in ("run", "farm") and "-o" not in words and "local-cluster" not in words:
        # One folder per job file, so a job's farm scripts, shards and status meet (and no other job's).
        job = next((w for w in words[2:] if w.endswith(".toml")), "job")
        words += ["-o", str(work / "job_out" / Path(job).stem)]
    return words


def main():
    binary, repo = sys.argv[1], Path(sys.argv[2]).resolve()
    work = Path(sys.argv[3]).resolve() if len(sys.argv) > 3 else Path(tempfile.mkdtemp(prefix="seasim_docs_"))
    shutil.rmtree(work, ignore_errors=True)  # a command must not pass on what an earlier run left
    work.mkdir(parents=True)
    for name in ("scenes", "jobs", "docs", "data", "tests"):
        (work / name).symlink_to(repo / name)
    failures, ran, skipped = [], 0, []
    t0 = time.time()
    for doc in doc_files(repo):
        files = {}
        found = commands(doc, files)
        for name, content in files.items():
            (work / name).parent.mkdir(parents=True, exist_ok=True)
            (work / name).write_text(content, encoding="utf-8")
        for number, text in found:
            where = f"{doc.relative_to(repo)}:{number}"
            if text.startswith("!"):
                # A preparation that fails here (a GPU recipe's copy of a build it did not make) is
                # listed, not failed: a seasim command that needed its file fails in its place.
                p = subprocess.run(["bash", "-c", text[1:]], cwd=work, capture_output=True, text=True, timeout=60)
                print(f"[{time.time() - t0:5.0f} s] {where}: exit {p.returncode}: {text[1:]}", flush=True)
                if p.returncode != 0:
                    skipped.append(f"{where}: preparation failed here: {text[1:]}: {(p.stdout + p.stderr).strip()[-300:]}")
                continue
            text = re.sub(r"\[[^\]]*\]", "", text)  # optional arguments of a synopsis
            reason = next((r for pattern, r in EXCLUDED if re.search(pattern, text)), None)
            if reason:
                skipped.append(f"{where}: excluded ({reason}): {text}")
                continue
            words = shlex.split(text, comments=True)
            if any(PLACEHOLDER.match(w) for w in words[1:]):
                skipped.append(f"{where}: synopsis with placeholders: {text}")
                continue
            words = rewrite(words, binary, repo, work)
            env = dict(os.environ)
            if words[1:3] == ["cache", "clear"]:
                env["SEASIM_CACHE_DIR"] = str(work / "private-cache")
                env["POCL_CACHE_DIR"] = str(work / "private-pocl-cache")
            start = time.time()
            try:
                p = subprocess.run(words, cwd=work, env=env, capture_output=True, text=True, timeout=TIMEOUT_S)
                code, output = p.returncode, p.stdout + p.stderr
            except subprocess.TimeoutExpired:
                code, output = "timeout", f"over {TIMEOUT_S} s"
            ran += 1
            expected = next((r for pattern, r in EXPECTED_TO_FAIL if re.search(pattern, text)), None)
            if expected:
                code = 0 if code not in (0, "timeout") else f"{code} (expected to fail: {expected})"
            print(f"[{time.time() - t0:5.0f} s] {where}: exit {code} in {time.time() - start:.1f} s: {shlex.join(words[1:])}",
                  flush=True)
            if code != 0:
                failures.append(f"{where}: exit {code}: {shlex.join(words)}\n{output[-2000:]}")
    for s in skipped:
        print("not run: " + s)
    print(f"{ran} commands run, {len(skipped)} not run, {len(failures)} failed, {time.time() - t0:.0f} s")
    for f in failures:
        print("FAILED " + f)
    return 1 if failures or ran == 0 else 0


if __name__ == "__main__":
    sys.exit(main())
