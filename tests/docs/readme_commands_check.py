"""Doc-test of README.md: its commands exist, take the options it shows, name
files that exist, and print what it shows (ctest docs.readme_commands; python3
standard library only, no network).

Commands are the lines of the fenced sh/bash/console/text blocks (a `text`
block's commands are its `$ ` lines; the lines under one are the output it
shows) and the inline `splat ...`, `bash ...` and `python3 ...` spans. Checks,
each failure naming the README line and the rule:

- subcommand: `splat X` names a subcommand of `splat --help`;
- option: every `--option` of a splat command is in `splat X --help`, and a
  value of a choice option (`--format a|b`) is one of its choices; an inline
  `--option` span is an option of a subcommand named in its section;
- script-option: an `--option` given to a repository script appears in it;
- path: every repository path (scenes/, campaigns/, materials/, scripts/,
  docs/, schemas/, bench/, python/, ...) exists; a link's `#anchor` is a
  heading of its file;
- pointer: every `--set`/`--set-levels` JSON pointer is a field of
  schemas/scene.schema.json (`--set` creates missing objects, so the schema,
  not the scene file, says what may be set); an inline `--set` example, or
  an inline `{"base": ...}` material as the particle's, is also applied to
  the README's scene in a real run;
- material: every library material named exists, and the library has as
  many metals as the README says;
- run: the cheap commands run for real in a temporary folder (FE impacts at
  most 8 elements across, two-mass campaigns, `splat materials`, stores they
  made) and exit 0 within the time limit; /tmp/splat becomes that folder;
- output: each output line the README shows is printed, in order, with every
  number equal within the README's printed precision (wall-clock times
  excepted);
- produced: every /tmp/splat file the README names (not the output of a
  command left unrun) exists after the runs;
- ctest, route: a `ctest -L/-R` selects a label and a test that exist; a
  `curl` route is in api/README.md;
- python: each fenced python block runs (from the source folder, on the
  /tmp/splat files the README's runs made) and exits 0 within the time
  limit.

Commands not run (placeholders such as NAME or CAMPAIGN, `serve`, finer
ladders, Slurm) get every static check.

usage: readme_commands_check.py SPLAT SOURCE_DIR [WORK_DIR]
"""

import difflib
import glob
import json
import os
import re
import shlex
import shutil
import subprocess
import sys
import tempfile
import time

RUN_LIMIT_S = 45        # one command
WINDOW_LIMIT_S = 150    # one `splat window` (a campaign at 16 elements across)
CHEAP_ELEMENTS_ACROSS = 8
README_SCRATCH = "/tmp/splat"
README_SYSTEM = "/var/lib/splat"
REPO_DIRS = ("scenes", "campaigns", "materials", "scripts", "docs", "schemas", "bench",
             "python", "web", "api", "campaign", "solver", "tests", "app", "cmake")
PATH_RE = re.compile(r"(?<![\w/.~$-])((?:%s)/[\w.*/-]*)" % "|".join(REPO_DIRS))
LINK_RE = re.compile(r"\]\(([^)#\s]+)(?:#([^)\s]+))?\)")
NUMBER_RE = re.compile(r"(?<![\w.])[-+]?\d+(?:\.\d+)?(?:[eE][-+]?\d+)?(?![\w])")
PLACEHOLDER_RE = re.compile(r"(?<![\w$])[A-Z]{2,}(?![a-z])|\.\.\.|<\w+>")
VOLATILE = [(re.compile(r"wall \d+(?:\.\d+)? s"), "wall <seconds> s")]
SHELL_OPS = {"&&", "||", ";", "|"}


class Failures:
    def __init__(self):
        self.items = []

    def add(self, line, rule, message):
        if (line, rule, message) not in self.items:
            self.items.append((line, rule, message))


# ---- README parsing ---------------------------------------------------------

class Command:
    def __init__(self, line, text, argv, source, section):
        self.line = line          # README line of its first character
        self.text = text
        self.argv = argv
        self.source = source      # "block" or "inline"
        self.section = section    # heading it sits under
        self.shown = []           # (line, text) output lines the README shows
        self.ran = False


def split_commands(text):
    """shlex words of one shell line, split at &&, ||, ; and | (subshell
    parentheses dropped)."""
    lexer = shlex.shlex(text, posix=True, punctuation_chars="&|;")
    lexer.whitespace_split = True
    lexer.commenters = "#"
    words = [w for w in lexer]
    out, cur = [], []
    for w in words:
        if w in SHELL_OPS:
            out.append(cur)
            cur = []
            continue
        w = w[1:] if w.startswith("(") else w
        w = w[:-1] if w.endswith(")") and w.count("(") < w.count(")") else w
        if w:
            cur.append(w)
    out.append(cur)
    return [c for c in out if c]


def parse_readme(path):
    lines = open(path, encoding="utf-8").read().split("\n")
    commands, prose, blocks = [], [], []
    section = ""
    i = 0
    while i < len(lines):
        m = re.match(r"^\s*```(\w*)", lines[i])
        if m:
            lang, start = m.group(1), i + 1
            body = []
            i += 1
            while i < len(lines) and not re.match(r"^\s*```", lines[i]):
                body.append((i + 1, lines[i]))
                i += 1
            blocks.append((lang, start, body, section))
            i += 1
            continue
        if lines[i].startswith("#"):
            section = lines[i].lstrip("#").strip()
        prose.append((i + 1, lines[i], section))
        i += 1

    for lang, start, body, sec in blocks:
        if lang not in ("sh", "bash", "console", "shell", "text", ""):
            continue
        console = any(t.startswith("$ ") for _, t in body)
        if lang == "text" and not console:
            continue
        current = None
        j = 0
        while j < len(body):
            n, t = body[j]
            if console and not t.startswith("$ "):
                if current is not None and t.strip():
                    current.shown.append((n, t))
                j += 1
                continue
            t = t[2:] if console else t
            if not t.strip() or t.lstrip().startswith("#"):
                j += 1
                continue
            joined = t
            while joined.rstrip().endswith("\\") and j + 1 < len(body):
                j += 1
                joined = joined.rstrip()[:-1] + " " + body[j][1].strip()
            for argv in split_commands(joined):
                current = Command(n, joined, argv, "block", sec)
                commands.append(current)
            j += 1

    # Inline spans may wrap over a line break within a paragraph.
    text = "\n".join(t for _, t, _ in prose)
    line_of = [n for n, _, _ in prose]
    section_of = [s for _, _, s in prose]
    spans = []
    for m in re.finditer(r"`([^`]+)`", text):
        k = text.count("\n", 0, m.start())
        spans.append((line_of[k], " ".join(m.group(1).split()), section_of[k]))
    for n, span, sec in spans:
        first = span.split()[0]
        if first in ("splat", "bash", "python3") or first.endswith("/splat"):
            for argv in split_commands(span):
                commands.append(Command(n, span, argv, "inline", sec))
    return lines, blocks, prose, spans, commands


def github_slug(heading):
    s = heading.strip().lower()
    s = re.sub(r"[^\w\- ]", "", s)
    return s.replace(" ", "-")


# ---- splat's own description of itself -------------------------------------

class Cli:
    def __init__(self, splat):
        self.splat = splat
        top = self.help([])
        sub = top.split("Subcommands:", 1)[1] if "Subcommands:" in top else ""
        self.subcommands = [m.group(1) for m in re.finditer(r"^\s{2}([\w-]+)\s", sub, re.M)]
        self.options = {}     # subcommand -> {option: takes_value}
        self.choices = {}     # subcommand -> {option: [choices]}
        self.required = {}    # subcommand -> (positionals, options)
        for s in self.subcommands:
            h = self.help([s])
            opts, choices, req_opts, req_pos = {"--help": False}, {}, [], []
            block = h.split("Options:", 1)[1] if "Options:" in h else ""
            for m in re.finditer(r"^\s{2}(?:-\w,)?(--[\w-]+)(?: (\S+))?", block, re.M):
                name, after = m.group(1), m.group(2) or ""
                opts[name] = bool(re.match(r"(TEXT|INT|UINT|FLOAT|NUMBER)\b", after))
                c = re.match(r"TEXT:\{([^}]*)\}", after)
                if c:
                    choices[name] = c.group(1).split(",")
            for m in re.finditer(r"^\s{2}(--[\w-]+) \S+ REQUIRED", block, re.M):
                req_opts.append(m.group(1))
            if "Positionals:" in h:
                pos = h.split("Positionals:", 1)[1].split("Options:", 1)[0]
                req_pos = re.findall(r"^\s{2}(\w+) \S+ REQUIRED", pos, re.M)
            self.options[s], self.choices[s], self.required[s] = opts, choices, (req_pos, req_opts)

    def help(self, args):
        p = subprocess.run([self.splat] + args + ["--help"], capture_output=True, text=True,
                           timeout=30)
        if p.returncode != 0:
            raise SystemExit(f"readme: `splat {' '.join(args)} --help` exited {p.returncode}")
        return p.stdout


def is_splat(argv):
    return argv and (argv[0] == "splat" or argv[0].endswith("/splat"))


def parse_splat(cli, argv):
    """(subcommand, positionals, [(option, value or None)]) of a splat argv."""
    sub = argv[1] if len(argv) > 1 else None
    opts, pos = [], []
    takes = cli.options.get(sub, {})
    k = 2
    while k < len(argv):
        w = argv[k]
        if w.startswith("--"):
            name, eq, val = w.partition("=")
            if eq:
                opts.append((name, val))
            elif takes.get(name) and k + 1 < len(argv):
                opts.append((name, argv[k + 1]))
                k += 1
            else:
                opts.append((name, None))
        else:
            pos.append(w)
        k += 1
    return sub, pos, opts


def has_placeholder(argv):
    return any(PLACEHOLDER_RE.search(w) for w in argv)


# ---- scene schema -----------------------------------------------------------

class SceneSchema:
    def __init__(self, path):
        self.root = json.load(open(path, encoding="utf-8"))

    def resolve(self, node):
        while isinstance(node, dict) and "$ref" in node:
            ref = node["$ref"]
            assert ref.startswith("#/"), ref
            node = self.root
            for part in ref[2:].split("/"):
                node = node[part]
        return node

    def alternatives(self, node):
        node = self.resolve(node)
        out = [node]
        for key in ("oneOf", "anyOf", "allOf"):
            for sub in node.get(key, []):
                out += self.alternatives(sub)
        for key in ("then", "else"):
            if key in node:
                out += self.alternatives(node[key])
        return out

    def missing_segment(self, pointer):
        """None if the schema defines the pointer's field, else (parent, segment)."""
        segs = [s.replace("~1", "/").replace("~0", "~") for s in pointer.split("/")[1:]]
        node = self.root
        for k, seg in enumerate(segs):
            nxt = None
            for alt in self.alternatives(node):
                if seg in alt.get("properties", {}):
                    nxt = alt["properties"][seg]
                    break
                if seg.isdigit() and "items" in alt:
                    nxt = alt["items"]
                    break
                if isinstance(alt.get("additionalProperties"), dict):
                    nxt = alt["additionalProperties"]
            if nxt is None:
                return "/" + "/".join(segs[:k]), seg
            node = nxt
        return None


# ---- checks -------------------------------------------------------------------

def check_paths(src, lines, fails):
    for n, t in enumerate(lines, 1):
        for m in LINK_RE.finditer(t):
            target, anchor = m.group(1), m.group(2)
            if re.match(r"\w+://", target):
                continue
            full = os.path.join(src, target)
            if not os.path.exists(full):
                fails.add(n, "path", f"link target {target} does not exist")
            elif anchor and full.endswith(".md"):
                heads = [github_slug(h.lstrip("#")) for h in open(full, encoding="utf-8")
                         if h.startswith("#")]
                if anchor not in heads:
                    fails.add(n, "path", f"{target} has no heading #{anchor}")
        for m in PATH_RE.finditer(t):
            p = m.group(1).rstrip(".")
            full = os.path.join(src, p)
            ok = glob.glob(full) if "*" in p else os.path.exists(full)
            if not ok:
                fails.add(n, "path", f"{p} does not exist in the repository")


def check_splat_static(cli, c, schema, fails):
    sub, pos, opts = parse_splat(cli, c.argv)
    if sub is None or (PLACEHOLDER_RE.fullmatch(sub) and sub.isupper()):
        return
    if sub not in cli.subcommands:
        fails.add(c.line, "subcommand",
                  f"`splat {sub}` is no subcommand (splat --help lists {', '.join(cli.subcommands)})")
        return
    for name, val in opts:
        if name not in cli.options[sub]:
            fails.add(c.line, "option", f"`splat {sub}` has no option {name} (splat {sub} --help)")
            continue
        choices = cli.choices[sub].get(name)
        if choices and val is not None and not PLACEHOLDER_RE.search(val):
            for v in val.split("|"):
                if v not in choices:
                    fails.add(c.line, "option",
                              f"{name} {v}: `splat {sub}` takes {'|'.join(choices)}")
        if name in ("--set", "--set-levels") and val is not None:
            check_pointer(c.line, name, val, schema, fails)


def check_pointer(line, option, value, schema, fails):
    pointer = value.split("=", 1)[0]
    if not pointer.startswith("/") or "=" not in value:
        fails.add(line, "pointer", f"{option} {value}: expected /json/pointer=VALUE")
        return
    miss = schema.missing_segment(pointer)
    if miss:
        fails.add(line, "pointer",
                  f"{option} {pointer}: schemas/scene.schema.json has no field '{miss[1]}' "
                  f"under {miss[0] or '/'}")


def check_inline_options(cli, spans, commands, fails):
    """An inline `--option ...` span is an option of a splat subcommand named
    in the same section (any subcommand where the section names none), or
    of a repository script the section runs."""
    by_section = {}
    for c in commands:
        if is_splat(c.argv) and len(c.argv) > 1 and c.argv[1] in cli.subcommands:
            by_section.setdefault(c.section, set()).add(c.argv[1])
    scripts = {}
    for c in commands:
        for w in c.argv:
            if re.match(r"(scripts|python)/.*\.(sh|py)$", w):
                scripts.setdefault(c.section, set()).add(w)
    for n, span, sec in spans:
        if not span.startswith("--"):
            continue
        argv = ["splat", "?"] + shlex.split(span)
        subs = sorted(by_section.get(sec, set())) or cli.subcommands
        name = argv[2].split("=", 1)[0]
        owners = [s for s in subs if name in cli.options[s]]
        in_script = [p for p in scripts.get(sec, set())
                     if re.search(r"(?<![\w-])%s(?![\w-])" % re.escape(name),
                                  open(os.path.join(cli.src, p), encoding="utf-8").read())]
        if not owners and not in_script:
            fails.add(n, "option", f"`{span}`: no option {name} in `splat "
                      f"{'|'.join(subs)} --help`" + (" nor in " + ", ".join(sorted(scripts[sec]))
                                                     if sec in scripts else ""))
            continue
        if owners:
            argv[1] = owners[0]
            errors = []
            for s in owners:
                f = Failures()
                check_splat_static(cli, Command(n, span, ["splat", s] + argv[2:], "inline", sec),
                                   cli.schema, f)
                errors.append(f.items)
            if all(errors):
                for e in errors[0]:
                    fails.add(*e)


def check_script_options(src, c, fails):
    for k, w in enumerate(c.argv):
        if re.match(r"(scripts|python)/.*\.(sh|py)$", w) and os.path.exists(os.path.join(src, w)):
            text = open(os.path.join(src, w), encoding="utf-8").read()
            for o in c.argv[k + 1:]:
                if o.startswith("--"):
                    name = o.split("=", 1)[0]
                    if not re.search(r"(?<![\w-])%s(?![\w-])" % re.escape(name), text):
                        fails.add(c.line, "script-option", f"{w} takes no option {name}")


def check_ctest(src, c, fails):
    args = c.argv
    cm = open(os.path.join(src, "tests", "CMakeLists.txt"), encoding="utf-8").read()
    labels = set(re.findall(r"foreach\(kind ([\w ]+)\)", cm)[0].split())
    labels |= set(re.findall(r"LABELS (\w+)", cm))
    label = args[args.index("-L") + 1] if "-L" in args else None
    if label is not None and label not in labels:
        fails.add(c.line, "ctest", f"no ctest label {label} (tests/CMakeLists.txt: {sorted(labels)})")
        return
    if "-R" in args:
        pattern = args[args.index("-R") + 1]
        names = []
        for f in glob.glob(os.path.join(src, "tests", label or "*", "*.cpp")):
            names += [f"{a}.{b}" for a, b in
                      re.findall(r"^TEST(?:_F|_P)?\((\w+),\s*(\w+)\)", open(f).read(), re.M)]
        if not any(re.search(pattern, x) for x in names):
            fails.add(c.line, "ctest", f"-R {pattern} selects no test in tests/{label or '*'}/")


def check_curl(src, c, fails):
    url = next((w for w in c.argv[1:] if "/api/v1/" in w), None)
    if url is None:
        return
    route = url.split("/api/v1", 1)[1].split("?")[0]
    route = re.sub(r"/\d+(?=/|$)", "/{id}", route)
    if route not in open(os.path.join(src, "api", "README.md"), encoding="utf-8").read():
        fails.add(c.line, "route", f"api/README.md lists no route {route}")


def check_materials(cli, lines, fails):
    p = subprocess.run([cli.splat, "materials", "--json"], capture_output=True, text=True,
                       timeout=30)
    names = {d["name"] for d in json.loads(p.stdout)}
    for n, t in enumerate(lines, 1):
        for m in re.finditer(r"\((\d+) metals", t):
            if int(m.group(1)) != len(names):
                fails.add(n, "material", f"the README says {m.group(1)} metals; "
                          f"`splat materials` lists {len(names)}")
        pats = [r"material=([\w-]+)", r'"material"\s*:\s*"([\w-]+)"', r'"base"\s*:\s*"([\w-]+)"',
                r"--(?:particle|substrate)[ =]([\w-]+)"]
        for pat in pats:
            for m in re.finditer(pat, t):
                name = m.group(1)
                if name.isupper() or name.endswith(".json"):
                    continue
                if name not in names:
                    fails.add(n, "material", f"no library material {name} (splat materials)")


# ---- running the cheap commands ---------------------------------------------

def impact_cost_ok(scene, sets):
    """True where every run of the scene is an FE impact at most 8 elements
    across, or a two-mass model."""
    try:
        doc = json.load(open(scene, encoding="utf-8"))
    except (OSError, ValueError):
        return False
    if "two_mass" in doc:
        return True
    pi = doc.get("particle_impact")
    if pi is None:
        return False
    across = [pi["particle"].get("elements_across", 12)]
    disc = pi["particle"].get("discretization", "auto")
    for s in sets:
        ptr, _, val = s.partition("=")
        if ptr == "/particle_impact/particle/elements_across":
            across = [int(v) for v in val.split(",")]
        if ptr == "/particle_impact/particle/discretization":
            disc = val
    return disc == "fe" and max(across) <= CHEAP_ELEMENTS_ACROSS


def campaign_cost_ok(path):
    try:
        doc = json.load(open(path, encoding="utf-8"))
    except (OSError, ValueError):
        return False
    if doc.get("executor") == "slurm":
        return False
    sets = []
    for f in doc.get("fields", []):
        sets.append(f["pointer"] + "=" + ",".join(str(v) for v in f.get("values", [])))
    scene = os.path.join(os.path.dirname(path), doc["base_scene"])
    return impact_cost_ok(scene, sets)


class Runner:
    def __init__(self, cli, src, work):
        self.cli, self.src, self.work = cli, src, work
        self.made = set()     # stores and folders the runs made

    def map_word(self, w):
        if w.startswith(README_SCRATCH):
            return os.path.join(self.work, "tmp-splat") + w[len(README_SCRATCH):]
        if w.startswith(README_SYSTEM):
            return os.path.join(self.work, "var-lib-splat") + w[len(README_SYSTEM):]
        if "/" in w and not w.startswith("/") and os.path.exists(os.path.join(self.src, w)):
            return os.path.join(self.src, w)
        return w

    def map_argv(self, argv):
        out = []
        for w in argv:
            if w.startswith("--") and "=" in w:
                name, _, val = w.partition("=")
                out.append(name + "=" + self.map_word(val))
            else:
                out.append(self.map_word(w))
        return out

    def plan(self, c):
        """(run it, why not)."""
        if not is_splat(c.argv):
            return False, "not splat"
        sub, pos, opts = parse_splat(self.cli, c.argv)
        if has_placeholder(c.argv):
            return False, "placeholders"
        if sub not in self.cli.subcommands:
            return False, "unknown subcommand"
        req_pos, req_opts = self.cli.required[sub]
        given = {o for o, _ in opts}
        if len(pos) < len(req_pos) or any(o not in given for o in req_opts):
            return False, "a reference, not a whole command"
        sets = [v for o, v in opts if o in ("--set", "--set-levels") and v]
        if sub == "serve":
            return False, "a server"
        if sub in ("run", "converge"):
            ok = impact_cost_ok(self.map_word(pos[0]), sets)
            return ok, "" if ok else "finer than 8 across or not FE"
        if sub in ("sweep", "regress"):
            ok = campaign_cost_ok(self.map_word(pos[0])) and \
                all(v != "slurm" for o, v in opts if o == "--executor")
            return ok, "" if ok else "finer than 8 across, or Slurm"
        if sub == "window":
            ok = all(v != "converged" for o, v in opts if o == "--accuracy")
            return ok, "" if ok else "--accuracy converged"
        if sub == "windows":
            db = dict(opts).get("--db") or "splat.db"
            ok = self.map_word(db) in self.made
            return ok, "" if ok else "its store comes from a command not run"
        if sub == "materials":
            return True, ""
        return False, "not known to be cheap"

    def run(self, c, fails):
        argv = self.map_argv(c.argv)
        argv[0] = self.cli.splat
        sub, pos, opts = parse_splat(self.cli, argv)
        for o, v in opts:
            if o == "--out" and v:
                os.makedirs(v, exist_ok=True)
            if o == "--db" and v:
                os.makedirs(os.path.dirname(v) or ".", exist_ok=True)
        env = dict(os.environ, OMP_WAIT_POLICY="passive")
        limit = WINDOW_LIMIT_S if sub == "window" else RUN_LIMIT_S
        t0 = time.monotonic()
        try:
            p = subprocess.run(argv, cwd=self.work, capture_output=True, text=True,
                               timeout=limit, env=env)
        except subprocess.TimeoutExpired:
            fails.add(c.line, "run", f"`{c.text}` took more than {limit} s")
            return
        c.ran = True
        print(f"readme: line {c.line}: ran `{c.text}` ({time.monotonic() - t0:.1f} s, "
              f"exit {p.returncode})")
        for o, v in opts:
            if o in ("--db", "--out") and v:
                self.made.add(v)
        if sub == "window" and "--db" not in dict(opts):
            self.made.add(os.path.join(self.work, "window.db"))
        if p.returncode != 0:
            tail = (p.stderr or p.stdout).strip().splitlines()[-3:]
            fails.add(c.line, "run", f"`{c.text}` exited {p.returncode}: " + " | ".join(tail))
            return
        if c.shown:
            actual = (p.stdout + p.stderr).replace(os.path.join(self.work, "tmp-splat"),
                                                   README_SCRATCH)
            compare_output(c, actual.splitlines(), fails)


def skeleton(t):
    for pat, rep in VOLATILE:
        t = pat.sub(rep, t)
    return " ".join(NUMBER_RE.sub("#", t).split())


def half_ulp(token):
    m = re.match(r"[-+]?\d+(?:\.(\d+))?(?:[eE]([-+]?\d+))?$", token)
    decimals = len(m.group(1) or "")
    exponent = int(m.group(2) or 0)
    return 0.5 * 10.0 ** (exponent - decimals)


def compare_output(c, actual, fails):
    skel = [skeleton(a) for a in actual]
    k = 0
    for n, shown in c.shown:
        if shown.strip() in ("...", "…"):
            continue
        want = skeleton(shown)
        hit = next((j for j in range(k, len(actual)) if skel[j] == want), None)
        if hit is None:
            near = difflib.get_close_matches(shown.strip(), [a.strip() for a in actual], 1, 0.3)
            fails.add(n, "output", f"`{c.text.split()[1]}` prints no line like this one "
                      f"(after README line {c.line}'s earlier lines); nearest: "
                      f"{near[0] if near else '(none)'}")
            continue
        k = hit + 1
        masked_shown, masked_actual = shown, actual[hit]
        for pat, rep in VOLATILE:
            masked_shown, masked_actual = pat.sub(rep, masked_shown), pat.sub(rep, masked_actual)
        for r, a in zip(NUMBER_RE.findall(masked_shown), NUMBER_RE.findall(masked_actual)):
            if abs(float(a) - float(r)) > half_ulp(r) * (1 + 1e-9):
                fails.add(n, "output", f"the README shows {r}, the build prints {a}: "
                          f"{actual[hit].strip()}")


def check_produced(runner, blocks, prose, commands, fails):
    """/tmp/splat paths the README names exist after the runs, except the
    --out/--db of commands left unrun (and output lines, compared above)."""
    skip = set()
    for c in commands:
        if not c.ran:
            for k, w in enumerate(c.argv[:-1]):
                if w in ("--out", "--db"):
                    skip.add(c.argv[k + 1])
    if not any(c.ran for c in commands):
        return
    texts = [(n, t) for n, t, _ in prose]
    for lang, start, body, _ in blocks:
        for n, t in body:
            if not (lang == "text" and not t.startswith("$ ")):
                texts.append((n, t))
    for n, t in texts:
        for m in re.finditer(re.escape(README_SCRATCH) + r"[\w./-]*", t):
            p = m.group(0).rstrip(".")
            if p in skip:
                continue
            if not os.path.exists(runner.map_word(p)):
                fails.add(n, "produced", f"{p}: the README's runs made no such file")
    for c in commands:
        if any(w.endswith("render_impact.py") for w in c.argv) and "--field" in c.argv:
            field = c.argv[c.argv.index("--field") + 1]
            xmf = runner.map_word(next(w for w in c.argv if w.endswith(".xmf")))
            if os.path.exists(xmf) and f'Name="{field}"' not in open(xmf).read():
                fails.add(c.line, "produced", f"--field {field}: no such array in {os.path.basename(xmf)}")


def check_python_blocks(runner, blocks, fails):
    """Each python block runs with this interpreter, from the source folder,
    its /tmp/splat paths mapped to the runs' folder, and exits 0."""
    for lang, start, body, _ in blocks:
        if lang != "python":
            continue
        code = "\n".join(t for _, t in body)
        paths = sorted(set(m.group(0) for m in
                           re.finditer(re.escape(README_SCRATCH) + r"[\w./-]*", code)))
        missing = [p for p in paths if not os.path.exists(runner.map_word(p))]
        if missing:
            fails.add(start, "python", f"{missing[0]}: the README's runs made no such file")
            continue
        for p in paths:
            code = code.replace(p, runner.map_word(p))
        try:
            r = subprocess.run([sys.executable, "-c", code], cwd=runner.src, capture_output=True,
                               text=True, timeout=RUN_LIMIT_S)
        except subprocess.TimeoutExpired:
            fails.add(start, "python", f"the block ran longer than {RUN_LIMIT_S} s")
            continue
        if r.returncode != 0:
            last = (r.stderr.strip().splitlines() or ["(no message)"])[-1]
            fails.add(start, "python", f"the block exits {r.returncode}: {last}")
        else:
            print(f"readme: line {start}: ran the python block (exit 0)")


# ---- main -----------------------------------------------------------------------

def main(argv):
    if len(argv) < 3:
        print(__doc__)
        return 2
    splat, src = os.path.abspath(argv[1]), os.path.abspath(argv[2])
    readme = os.path.join(src, "README.md")
    work = os.path.abspath(argv[3]) if len(argv) > 3 else tempfile.mkdtemp(prefix="readme-")
    shutil.rmtree(work, ignore_errors=True)
    os.makedirs(work)
    t0 = time.monotonic()

    fails = Failures()
    cli = Cli(splat)
    cli.src = src
    cli.schema = SceneSchema(os.path.join(src, "schemas", "scene.schema.json"))
    lines, blocks, prose, spans, commands = parse_readme(readme)
    print(f"readme: {len(commands)} commands, {len(spans)} inline spans in {readme}")

    check_paths(src, lines, fails)
    check_materials(cli, lines, fails)
    check_inline_options(cli, spans, commands, fails)
    runner = Runner(cli, src, work)
    for c in commands:
        prog = os.path.basename(c.argv[0])
        if is_splat(c.argv):
            check_splat_static(cli, c, cli.schema, fails)
        elif prog == "ctest":
            check_ctest(src, c, fails)
        elif prog == "curl":
            check_curl(src, c, fails)
        check_script_options(src, c, fails)
        if c.argv[0] == "build/app/splat" and not splat.endswith("/app/splat"):
            fails.add(c.line, "path", f"build/app/splat: the build puts splat at {splat}")
        ok, why = runner.plan(c)
        if ok:
            runner.run(c, fails)
        elif is_splat(c.argv) and why not in ("not splat",):
            print(f"readme: line {c.line}: not run ({why}): `{c.text}`")

    # Inline --set examples, applied to the scene of the README's last run
    # before them.
    scene = None
    for n, span, sec in spans:
        earlier = [c for c in commands if c.line < n and is_splat(c.argv)
                   and len(c.argv) > 2 and c.argv[1] == "run"]
        if earlier:
            scene = earlier[-1].argv[2]
        if span.startswith("{") and '"base"' in span and scene:
            # An inline material document, as the particle's material.
            span = "--set '/particle_impact/particle/material=%s'" % span
        if span.startswith("--set ") and scene:
            words = shlex.split(span)
            c = Command(n, f"splat run {scene} --threads 1 --out {README_SCRATCH}/set-example "
                        + span, ["splat", "run", scene, "--threads", "1", "--out",
                                 README_SCRATCH + "/set-example"] + words, "inline", sec)
            check_pointer(n, "--set", words[1], cli.schema, fails)
            if not fails.items or fails.items[-1][0] != n:
                runner.run(c, fails)

    check_produced(runner, blocks, prose, commands, fails)
    check_python_blocks(runner, blocks, fails)

    ran = sum(c.ran for c in commands)
    print(f"readme: {ran} commands run, {len(commands) - ran} checked without running, "
          f"{time.monotonic() - t0:.1f} s")
    for line, rule, message in sorted(fails.items):
        print(f"README.md:{line}: [{rule}] {message}")
    if fails.items:
        print(f"readme: {len(fails.items)} failure(s)")
        return 1
    shutil.rmtree(work, ignore_errors=True)
    print("readme: every command checked")
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv))
