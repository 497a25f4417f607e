#!/usr/bin/env python3
"""Runs the catalogue of bad inputs (tests/errors/catalogue.json) against a
plab binary, end to end through the command line, and checks each refusal:
the exit code (never 128 or more: no crash, no kill), the time it took and
the words the message must hold (the JSON path first of them).

    python3 tests/errors/run_catalogue.py build/plab [--only NAME[,NAME]] [--docs docs/errors.md]

One line per entry: PASS, FAIL (with the reason and the message), HANG (the
time bound ran out: the process group was killed), PENDING (an entry whose
fix has not landed: its result is shown but not counted) or SKIP (it needs
something this build does not have, e.g. the test plug-ins). The exit code
is 1 when any entry FAILs or HANGs. With --docs the table of messages is
written (docs/errors.md), from the first error line plab printed.

The catalogue's format is described at the top of catalogue.json. Python 3
standard library only.
"""

import argparse
import copy
import json
import os
import re
import resource
import shutil
import signal
import subprocess
import sys
import tempfile
import time

HERE = os.path.dirname(os.path.abspath(__file__))
DEFAULT_ARGV = ["run", "{scene}", "--quiet", "--out", "out"]


def fail(msg):
    sys.exit("run_catalogue.py: " + msg)


# ---------------------------------------------------------------- the input

def pointer_parts(pointer, entry):
    if not pointer.startswith("/"):
        fail(f"{entry}: patch path {pointer!r} must start with '/' (a JSON pointer, e.g. /bodies/0/radius)")
    return [p.replace("~1", "/").replace("~0", "~") for p in pointer[1:].split("/")]


def patch(scene, p, entry, raw_values):
    """One patch: {"set": POINTER, "value": V} (or "raw": TEXT, written into
    the file as it stands, e.g. 1e400) or {"delete": POINTER}. "-" as the last
    array index appends."""
    op = "set" if "set" in p else "delete" if "delete" in p else None
    if op is None:
        fail(f"{entry}: a patch is {{\"set\": path, \"value\": v}} or {{\"delete\": path}}, got {p}")
    parts = pointer_parts(p[op], entry)
    node = scene
    for k in parts[:-1]:
        node = node[int(k)] if isinstance(node, list) else node[k]
    last = parts[-1]
    if op == "delete":
        if isinstance(node, list):
            del node[int(last)]
        else:
            del node[last]
        return
    if "raw" in p:
        value = f"@@raw{len(raw_values)}@@"
        raw_values.append(p["raw"])
    else:
        value = copy.deepcopy(p["value"])
    if isinstance(node, list):
        if last == "-":
            node.append(value)
        else:
            node[int(last)] = value
    else:
        node[last] = value


def substitute(value, subs):
    if isinstance(value, str):
        for k, v in subs.items():
            value = value.replace("{" + k + "}", v)
        return value
    if isinstance(value, list):
        return [substitute(v, subs) for v in value]
    if isinstance(value, dict):
        return {k: substitute(v, subs) for k, v in value.items()}
    return value


def scene_text(entry, catalogue, subs):
    """The scene file's bytes, or None when the entry writes none."""
    name = entry["name"]
    if "text" in entry:
        return entry["text"].encode("utf-8", "surrogatepass")
    if "nest" in entry:  # {"nest": N, "at": KEY}: KEY holds N arrays one inside the other
        spec = entry["nest"]
        depth = spec["depth"]
        return ('{"dimension": 2, "%s": ' % spec["at"] + "[" * depth + "]" * depth + "}").encode()
    if "base" not in entry:
        return None
    bases = catalogue["base_scenes"]
    if entry["base"] not in bases:
        fail(f"{name}: unknown base scene {entry['base']!r}; base scenes: {', '.join(bases)}")
    scene = copy.deepcopy(bases[entry["base"]]["scene"])
    raw_values = []
    for p in entry.get("patches", []):
        patch(scene, substitute(p, subs), name, raw_values)
    text = json.dumps(scene, indent=1)
    for i, raw in enumerate(raw_values):
        text = text.replace(f'"@@raw{i}@@"', raw)
    return (text + entry.get("suffix", "")).encode("utf-8", "surrogatepass")


def run_setup(step, folder, plab, env, name):
    """Steps that prepare the files of an entry before the checked command."""
    if "plab" in step:  # a command that must succeed, e.g. a run that writes a checkpoint
        r = subprocess.run([plab] + step["plab"], cwd=folder, env=env, capture_output=True, timeout=60)
        if r.returncode != 0:
            raise RuntimeError(f"setup step plab {' '.join(step['plab'])} exited {r.returncode}: "
                               + (r.stderr + r.stdout).decode(errors="replace")[:500])
        return
    path = os.path.join(folder, step["file"])
    data = bytearray(open(path, "rb").read())
    if "keep" in step:  # truncate to this fraction of the file (or this many bytes when > 1)
        keep = step["keep"]
        data = data[: int(len(data) * keep) if keep <= 1 else int(keep)]
    elif "replace" in step:  # the first occurrence of one text by another of the same length
        old, new = step["replace"].encode(), step["with"].encode()
        if old not in data:
            raise RuntimeError(f"setup: {step['replace']!r} is not in {step['file']}")
        i = data.index(old)
        data[i:i + len(old)] = new
    elif "poke" in step:  # bytes (hex) written at an offset
        b = bytes.fromhex(step["hex"])
        data[step["poke"]:step["poke"] + len(b)] = b
    elif "swap" in step:  # two bytes exchanged
        i, j = step["swap"]
        data[i], data[j] = data[j], data[i]
    else:
        fail(f"{name}: unknown setup step {step}")
    open(path, "wb").write(bytes(data))


# ---------------------------------------------------------------- a run

def limit_memory(mb):
    def preexec():
        if mb > 0:
            resource.setrlimit(resource.RLIMIT_AS, (mb << 20, mb << 20))
        resource.setrlimit(resource.RLIMIT_CORE, (0, 0))
    return preexec


def run_plab(argv, folder, env, seconds, memory_mb):
    """(return code or None when killed at the bound, stdout, stderr, seconds)."""
    t0 = time.monotonic()
    proc = subprocess.Popen(argv, cwd=folder, env=env, stdin=subprocess.DEVNULL, stdout=subprocess.PIPE,
                            stderr=subprocess.PIPE, start_new_session=True, preexec_fn=limit_memory(memory_mb))
    try:
        out, err = proc.communicate(timeout=seconds)
        rc = proc.returncode
    except subprocess.TimeoutExpired:
        try:
            os.killpg(proc.pid, signal.SIGKILL)
        except ProcessLookupError:
            pass
        out, err = proc.communicate()
        rc = None
    return rc, out.decode(errors="replace"), err.decode(errors="replace"), time.monotonic() - t0


def describe_rc(rc, seconds=None):
    if rc is None:
        return f"no answer within {seconds:g} s (killed)" if seconds else "killed at the time bound"
    if rc < 0:
        return f"killed by signal {-rc} ({signal.Signals(-rc).name})"
    return f"exit {rc}"


TIMESTAMP = re.compile(r"^\[\d{4}-\d\d-\d\d [\d:.]+\] ")


def first_message_line(out, err, word):
    """The first line of the answer: the first line saying `word` (error, or
    warning), on stderr, then on stdout (where the run's log goes), else the
    first line of stderr or of stdout."""
    texts = [[TIMESTAMP.sub("", l).rstrip() for l in t.splitlines() if l.strip()] for t in (err, out)]
    for lines in texts:
        for l in lines:
            if re.search(r"\b" + word + r"\b", l, re.I):
                return l
    for lines in texts:
        if lines:
            return lines[0]
    return ""


def same_files(a, b):
    """Whether folders a and b hold the same files, byte for byte."""
    try:
        names = sorted(os.listdir(a))
        if names != sorted(os.listdir(b)):
            return False
        for n in names:
            with open(os.path.join(a, n), "rb") as x, open(os.path.join(b, n), "rb") as y:
                if x.read() != y.read():
                    return False
        return True
    except OSError:
        return False


class Runner:
    def __init__(self, plab, catalogue, memory_mb, pending_seconds=None, test_plugins=None):
        self.pending_seconds = pending_seconds
        self.plab = os.path.abspath(plab)
        self.catalogue = catalogue
        self.memory_mb = memory_mb
        self.defaults = catalogue.get("defaults", {})
        bindir = os.path.dirname(self.plab)
        self.env = dict(os.environ)
        self.env.setdefault("OMP_NUM_THREADS", "1")
        # Under AddressSanitizer an address-space limit stops the process
        # before main (ASan reserves terabytes of shadow); let ASan hold the
        # memory down instead.
        with open(self.plab, "rb") as f:
            self.asan = b"__asan_init" in f.read() or "ASAN_OPTIONS" in os.environ
        if self.asan and memory_mb > 0:
            self.env["ASAN_OPTIONS"] = ":".join(filter(None, [self.env.get("ASAN_OPTIONS"), f"hard_rss_limit_mb={memory_mb}",
                                                              "allocator_may_return_null=1"]))
            self.memory_mb = 0
        # A build's plug-ins lie in <build>/plab_plugins, which that plab
        # searches; a plab copied elsewhere with its plug-in folder beside it
        # finds them through PLAB_PLUGIN_PATH (unless a folder it searches
        # holds the same files: then the messages listing the plug-ins found
        # would name each twice).
        self.search_dirs = self.plugin_search_dirs()
        beside = os.path.join(bindir, "plab_plugins")
        if os.path.isdir(beside) and not any(same_files(beside, d) for d in self.search_dirs):
            self.env["PLAB_PLUGIN_PATH"] = beside + (":" + self.env["PLAB_PLUGIN_PATH"] if self.env.get("PLAB_PLUGIN_PATH") else "")
            self.search_dirs = self.plugin_search_dirs()
        test_plugins = os.path.abspath(test_plugins or os.path.join(bindir, "test_plugins"))
        self.subs = {"test_plugins": test_plugins, "plab": self.plab}
        self.have = {"test_plugins": os.path.isfile(os.path.join(test_plugins, "wrong_abi.so"))}

    def plugin_search_dirs(self):
        r = subprocess.run([self.plab, "plugins"], env=self.env, capture_output=True, text=True, timeout=60)
        dirs, inside = [], False
        for line in r.stdout.splitlines():
            if line.startswith("plug-in search path"):
                inside = True
            elif inside and line.startswith("  "):
                dirs.append(line.strip())
            else:
                inside = False
        return dirs

    def stable_text(self, text, folder):
        """A message with the machine's folders replaced by placeholders."""
        real = os.path.realpath(folder)
        for f in {folder, real}:
            text = text.replace(f + "/", "").replace(f, ".")
        text = text.replace(self.subs["test_plugins"], "<test_plugins>")
        for d in sorted(self.search_dirs, key=len, reverse=True):
            text = text.replace(d, "<plugins>")
        text = re.sub(r"/\S*/validation/reference", "<source>/validation/reference", text)
        return text

    def run_entry(self, e):
        d = dict(self.defaults)
        d.update(e)
        result = {"name": e["name"], "entry": e, "line": "", "seconds": 0.0}
        needs = e.get("requires")
        if needs and not self.have.get(needs, False):
            result.update(status="SKIP", reason=f"needs {needs} (none in {self.subs[needs]})")
            return result
        folder = tempfile.mkdtemp(prefix="plab_errors_")
        try:
            text = scene_text(e, self.catalogue, self.subs)
            if text is not None:
                with open(os.path.join(folder, "scene.json"), "wb") as f:
                    f.write(text)
            for name, content in e.get("files", {}).items():
                with open(os.path.join(folder, name), "w") as f:
                    f.write(content)
            for name in e.get("dirs", []):
                os.makedirs(os.path.join(folder, name), exist_ok=True)
            subs = dict(self.subs, scene="scene.json", dir=folder)
            for step in e.get("setup", []):
                run_setup(substitute(step, subs), folder, self.plab, self.env, e["name"])
            argv = [self.plab] + substitute(e.get("argv", DEFAULT_ARGV) + e.get("args", []), subs)
            seconds = d.get("seconds", 10)
            if e.get("pending") and self.pending_seconds is not None:
                seconds = min(seconds, self.pending_seconds)
            memory = 0 if self.asan else d.get("memory_mb", self.memory_mb)
            rc, out, err, took = run_plab(argv, folder, self.env, seconds, memory)
            result["seconds"] = took
            result["bound"] = seconds
            result["rc"] = rc
            word = "warning" if d.get("warning") else "error"
            result["line"] = self.stable_text(first_message_line(out, err, word), folder)
            text_all = self.stable_text(err + out, folder)
            result["output"] = text_all
            want = d.get("exit", 2)
            missing = [c for c in d.get("contains", []) if self.stable_text(substitute(c, subs), folder) not in text_all]
            problems = []
            if rc is None:
                status = "HANG"
                problems.append(f"no answer within {seconds} s")
            elif rc < 0 or rc >= 128:
                status = "FAIL"
                problems.append(describe_rc(rc) + " (a crash or a kill, never an answer)")
            else:
                status = "PASS"
                if rc != want:
                    problems.append(f"exit {rc}, expected {want}")
                if missing:
                    problems.append("message lacks " + ", ".join(repr(m) for m in missing))
                if problems:
                    status = "FAIL"
            result.update(status=status, reason="; ".join(problems))
            if e.get("pending"):
                result["fixed"] = status == "PASS"
                result["now"] = status
                result["status"] = "PENDING"
        except (RuntimeError, subprocess.TimeoutExpired, OSError) as x:
            result.update(status="FAIL", reason=f"setup: {x}")
        finally:
            shutil.rmtree(folder, ignore_errors=True)
        return result


# ---------------------------------------------------------------- the docs

def code(text):
    # a run of one character (a 300-letter name, deep brackets) shown short
    text = re.sub(r"(.)\1{19,}", lambda m: m[1] * 8 + "…", text)
    text = text.replace("|", "\\|")
    return f"`` {text} ``" if "`" in text else f"`{text}`"


def cell(text):
    return text.replace("|", "\\|").replace("\n", " ")


def write_docs(path, catalogue, results):
    by_name = {r["name"]: r for r in results}
    lines = list(catalogue["docs"]["introduction"])
    lines.append("")
    for kind in catalogue["docs"]["sections"]:
        rows = [e for e in catalogue["entries"] if e["kind"] == kind["kind"]]
        if not rows:
            continue
        lines += ["", f"## {kind['title']}", ""]
        if kind.get("text"):
            lines += kind["text"] + [""]
        lines += ["| Bad input | Message |", "|---|---|"]
        for e in rows:
            r = by_name.get(e["name"])
            what = cell(e["what"])
            if r is None or r["status"] == "SKIP":
                msg = "*(not run: " + (r["reason"] if r else "left out by --only") + ")*"
            elif e.get("pending"):
                now = code(r["line"]) if r["line"] else "no message"
                msg = (f"*pending ({cell(e['pending'])}): to be refused with exit {e.get('exit', 2)}, naming "
                       + ", ".join(code(c) for c in e.get("contains", [])) + f"; plab now: {describe_rc(r['rc'], r.get('bound'))}"
                       + (f", {now}" if r["line"] else "") + "*")
            else:
                msg = code(r["line"])
                if e.get("warning"):
                    what += " (a warning; the run goes on)"
            lines.append(f"| {what} | {msg} |")
    unknown = {e["kind"] for e in catalogue["entries"]} - {k["kind"] for k in catalogue["docs"]["sections"]}
    if unknown:
        fail("entries of kinds without a docs section: " + ", ".join(sorted(unknown)))
    with open(path, "w") as f:
        f.write("\n".join(lines).rstrip() + "\n")


# ---------------------------------------------------------------- main

def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("plab", help="the plab binary")
    ap.add_argument("--catalogue", default=os.path.join(HERE, "catalogue.json"))
    ap.add_argument("--only", help="comma-separated entry names")
    ap.add_argument("--docs", help="write the table of messages to this file (docs/errors.md)")
    ap.add_argument("--memory-mb", type=int, default=2048,
                    help="address-space limit of each plab run in MiB (0: none; a plab built with ASan gets "
                         "ASan's hard_rss_limit_mb instead), default 2048")
    ap.add_argument("--pending-seconds", type=float,
                    help="a shorter time bound for the pending entries (default: their own), for quick runs")
    ap.add_argument("--test-plugins", help="the folder of the deliberately broken test plug-ins (default: "
                    "test_plugins beside plab); the entries that need them are skipped without it")
    ap.add_argument("--verbose", action="store_true", help="print the whole output of every entry")
    a = ap.parse_args()

    with open(a.catalogue) as f:
        catalogue = json.load(f)
    entries = catalogue["entries"]
    names = [e["name"] for e in entries]
    dup = {n for n in names if names.count(n) > 1}
    if dup:
        fail("entry names used twice: " + ", ".join(sorted(dup)))
    if a.only:
        wanted = a.only.split(",")
        unknown = [n for n in wanted if n not in names]
        if unknown:
            fail("no entry named " + ", ".join(unknown))
        entries = [e for e in entries if e["name"] in wanted]
    if not os.access(a.plab, os.X_OK):
        fail(f"{a.plab} is not an executable plab")

    runner = Runner(a.plab, catalogue, a.memory_mb, a.pending_seconds, a.test_plugins)
    t0 = time.monotonic()
    results, width = [], max(len(e["name"]) for e in entries)
    for e in entries:
        r = runner.run_entry(e)
        results.append(r)
        tag = r["status"]
        detail = ""
        if tag == "PENDING":
            detail = f"({e['pending']}) " + ("now passes: remove the pending flag" if r["fixed"]
                                              else f"not yet: {r['reason']}")
        elif tag != "PASS":
            detail = r["reason"]
        print(f"{tag:8} {r['seconds']:6.2f} s  {e['name']:{width}}  {detail}".rstrip(), flush=True)
        if (tag in ("FAIL", "HANG") and r.get("output") is not None) or a.verbose:
            for l in (r.get("output") or "").splitlines()[:8]:
                print("           | " + l[:300])
    total = time.monotonic() - t0
    count = {s: sum(r["status"] == s for r in results) for s in ("PASS", "FAIL", "HANG", "PENDING", "SKIP")}
    print(f"{len(results)} entries in {total:.1f} s: " + ", ".join(f"{n} {s.lower()}" for s, n in count.items() if n))
    if a.docs:
        if a.only:
            fail("--docs writes the whole table: leave out --only")
        write_docs(a.docs, catalogue, results)
        print("wrote " + a.docs)
    return 1 if count["FAIL"] or count["HANG"] else 0


if __name__ == "__main__":
    sys.exit(main())
