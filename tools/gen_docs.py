#!/usr/bin/env python3
"""Generate bouncer's command reference, man pages and bash completion from its own help.

Everything here is read from the built executable at build time, so none of it can go
stale: `bouncer --help` lists the commands, `bouncer CMD --help` gives each command's
description, usage and options (CLI11's format: a description line, `Usage: ...`, then
`Positionals:` / `Options:` sections of `  NAME [TYPE] [...] [REQUIRED]   description`).

    tools/gen_docs.py --bouncer build/tools/bouncer \
        [--docs DIR]            DIR/reference/index.md, DIR/reference/CMD.md,
                                DIR/reference/python.md (the package's __all__, from its
                                sources), DIR/reference/cpp.md (the public headers:
                                their comments and declarations, tools/cpp_api.py),
                                DIR/pictures/*.png (copied from data/pictures/)
        [--man DIR]             DIR/bouncer.1, DIR/bouncer-CMD.1 (roff, section 1)
        [--completion FILE]     a bash completion script for bouncer

Plain python3 (standard library only). Exit 1 when the executable fails or its help cannot
be parsed; nothing is written then.
"""
import argparse
import os
import re
import shutil
import subprocess
import sys
from dataclasses import dataclass, field

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
sys.dont_write_bytecode = True  # no tools/__pycache__ in the source tree
import cpp_api  # noqa: E402  (tools/cpp_api.py: the C++ API page, and the Markdown escaping both pages use)
from cpp_api import md_escape  # noqa: E402


@dataclass
class Option:
    names: list          # ["-h", "--help"] or ["file"] for a positional
    value: str           # the value's type word (NUMBER, PATH, on|off, ...) or "" for a flag
    repeat: bool         # "..." after the type: several values
    required: bool
    help: str
    positional: bool = False

    def words(self):
        """Values the completion offers: alternatives named in the type or the help."""
        if "|" in self.value:
            return self.value.split("|")
        if " | " not in self.help:
            return []
        text = re.sub(r"\s*\([^)]*\)", "", self.help)
        pieces = text.split(" | ")
        out = []
        for i, piece in enumerate(pieces):
            tokens = piece.split()
            if not tokens:
                continue
            word = tokens[-1] if i == 0 else tokens[0]
            word = word.rstrip(",;.")
            word = re.sub(r"[A-Z][A-Z0-9,:.]*$", "", word)  # mpfr:BITS -> mpfr:, knots:0:H0,... -> knots:0:
            if word.startswith("knots:"):
                word = "knots:"
            if re.fullmatch(r"[a-z][a-z0-9:._-]*", word):
                out.append(word)
        return out if len(out) >= 2 else []


@dataclass
class Command:
    name: str
    summary: str
    usage: str
    options: list = field(default_factory=list)
    help_text: str = ""


def run_help(bouncer, args):
    p = subprocess.run([bouncer, *args, "--help"], capture_output=True, text=True)
    if p.returncode != 0:
        sys.exit(f"gen_docs: `{' '.join([bouncer, *args, '--help'])}` exited {p.returncode}: {p.stderr.strip()}")
    return p.stdout


def parse_help(name, text):
    lines = text.rstrip("\n").split("\n")
    summary = lines[0].strip()
    usage = next((l[len("Usage: "):].strip() for l in lines if l.startswith("Usage: ")), None)
    if not summary or usage is None:
        sys.exit(f"gen_docs: cannot parse the help of {name or 'bouncer'}: no description or Usage line")
    cmd = Command(name, summary, usage, help_text=text.rstrip("\n"))
    section = None
    for line in lines[1:]:
        if re.fullmatch(r"[A-Z][A-Za-z]*:", line):
            section = line[:-1]
            continue
        if section not in ("Options", "Positionals"):
            continue
        if not line.strip():
            section = None if cmd.options else section
            continue
        if re.match(r"^ {4,}\S", line) and cmd.options:  # continuation of the last description
            cmd.options[-1].help = (cmd.options[-1].help + " " + line.strip()).strip()
            continue
        m = re.match(r"^  (\S+)((?: \S+)*?)(?: {2,}(.*))?$", line)
        if not m:
            sys.exit(f"gen_docs: cannot parse an option line of {name}: {line!r}")
        names = m.group(1).split(",")
        rest = m.group(2).split()
        repeat, required = "..." in rest, "REQUIRED" in rest
        rest = [r for r in rest if r not in ("...", "REQUIRED")]
        if len(rest) > 1:
            sys.exit(f"gen_docs: more than one value type in an option line of {name}: {line!r}")
        positional = section == "Positionals"
        value = rest[0] if rest else ""
        cmd.options.append(Option(names, value, repeat, required, (m.group(3) or "").strip(),
                                  positional))
    return cmd


def commands_of(top_help):
    out, inside = [], False
    for line in top_help.split("\n"):
        if line.startswith("Subcommands:"):
            inside = True
            continue
        if inside:
            m = re.match(r"^  ([a-z][a-z-]*) {2,}(.*)$", line)
            if m:
                out.append(m.group(1))
            elif line.strip() == "" and out:
                break
    if not out:
        sys.exit("gen_docs: `bouncer --help` lists no subcommands")
    return out


# ---------------------------------------------------------------- Markdown reference pages

def option_signature(o):
    sig = ", ".join(o.names)
    if o.value:
        sig += " " + o.value
    if o.repeat:
        sig += " ..."
    return sig


def reference_page(cmd, version):
    out = [f"# bouncer {cmd.name}", "", md_escape(cmd.summary), "", "```", cmd.usage, "```", ""]
    for title, pos in (("Arguments", True), ("Options", False)):
        opts = [o for o in cmd.options if o.positional == pos]
        if not opts:
            continue
        out += [f"## {title}", ""]
        for o in opts:
            req = " (required)" if o.required else ""
            out.append(f"- `{option_signature(o)}`{req}: {md_escape(o.help)}")
        out.append("")
    out += ["## Help as printed", "",
            f"This page is generated from `bouncer {cmd.name} --help` of {md_escape(version)} by "
            "`tools/gen_docs.py`; the same text is `man bouncer-" + cmd.name + "` and `bouncer help " +
            cmd.name + "`.", "", "```text", cmd.help_text, "```", ""]
    return "\n".join(out)


def reference_index(top, cmds):
    out = ["# Command reference", "",
           "One page per command, generated at build time from the command's own `--help` "
           "(`tools/gen_docs.py`), so it always matches the executable. The same pages are "
           "installed as man pages (`man bouncer`, `man bouncer-orbit`, ...).", "",
           "```text", top.help_text, "```", "", "| command | what it does |", "|---|---|"]
    for c in cmds:
        out.append(f"| [`{c.name}`]({c.name}.md) | {md_escape(c.summary).replace('|', '&#124;')} |")
    return "\n".join(out) + "\n"


# ---------------------------------------------------------------- roff man pages

def roff_escape(s):
    s = s.replace("\\", "\\e").replace("-", "\\-")
    return s


def roff_line(s):
    s = roff_escape(s)
    return "\\&" + s if s[:1] in (".", "'") else s


def man_page(cmd, version, all_names):
    title = "BOUNCER" if cmd.name is None else "BOUNCER-" + cmd.name.upper()
    page = "bouncer" if cmd.name is None else "bouncer-" + cmd.name
    out = [f'.TH "{title}" "1" "" "{roff_escape(version)}" "User Commands"',
           ".SH NAME", f"{roff_escape(page)} \\- {roff_line(cmd.summary)}", ".SH SYNOPSIS"]
    usage = cmd.usage.split(" ")
    out.append(".B " + roff_escape(" ".join(usage[:2] if cmd.name else usage[:1])))
    rest = usage[2:] if cmd.name else usage[1:]
    if rest:
        out.append(roff_line(" ".join(rest)))
    out += [".SH DESCRIPTION", roff_line(cmd.summary + ".")]
    if cmd.name is None:
        out += [".PP", roff_line("Every command has its own page, bouncer-COMMAND(1), and prints the same "
                                  "text with bouncer COMMAND --help or bouncer help COMMAND."),
                ".SH COMMANDS"]
        for c in all_names:
            out += [".TP", f".B {roff_escape(c.name)}", roff_line(c.summary)]
    for title, pos in (("ARGUMENTS", True), ("OPTIONS", False)):
        opts = [o for o in cmd.options if o.positional == pos]
        if not opts:
            continue
        out.append(f".SH {title}")
        for o in opts:
            sig = ", ".join(f"\\fB{roff_escape(n)}\\fR" for n in o.names)
            if o.value:
                sig += f" \\fI{roff_escape(o.value)}\\fR"
            if o.repeat:
                sig += " ..."
            if o.required:
                sig += " (required)"
            out += [".TP", sig, roff_line(o.help)]
    out.append(".SH SEE ALSO")
    if cmd.name is None:
        refs = [f"bouncer\\-{roff_escape(c.name)} (1)" for c in all_names]
    else:
        refs = ["bouncer (1)"]
    out += [f".BR {r}{',' if i + 1 < len(refs) else ''}" for i, r in enumerate(refs)]
    out += [".PP", roff_line("Generated from the program's --help by tools/gen_docs.py.")]
    return "\n".join(out) + "\n"


# ---------------------------------------------------------------- bash completion

FILE_TYPES = {"PATH", "FILE", "PREFIX", "DIR", "TEXT"}


def completion_script(top, cmds):
    names = " ".join(c.name for c in cmds)
    top_opts = " ".join(n for o in top.options for n in o.names)
    lines = ["# bash completion for bouncer: generated by tools/gen_docs.py from `bouncer --help`",
             "# and each `bouncer COMMAND --help`; do not edit (rebuild to regenerate).",
             "_bouncer() {",
             "  local cur prev cmd i opts words",
             "  COMPREPLY=()",
             '  cur=${COMP_WORDS[COMP_CWORD]}',
             '  prev=${COMP_WORDS[COMP_CWORD-1]}',
             '  cmd=""',
             "  for ((i = 1; i < COMP_CWORD; i++)); do",
             '    case ${COMP_WORDS[i]} in -*) ;; *) cmd=${COMP_WORDS[i]}; break ;; esac',
             "  done",
             f'  if [[ -z $cmd ]]; then',
             f'    COMPREPLY=($(compgen -W "{names} help {top_opts}" -- "$cur")); return 0',
             "  fi",
             f'  if [[ $cmd == help ]]; then',
             f'    [[ $prev == help ]] && COMPREPLY=($(compgen -W "{names}" -- "$cur")); return 0',
             "  fi",
             '  case $cmd in']
    for c in cmds:
        opts = " ".join(n for o in c.options if not o.positional for n in o.names)
        lines.append(f'    {c.name})')
        lines.append(f'      opts="{opts}"')
        values = []  # (option names, words or FILE)
        for o in c.options:
            if o.positional or not o.value:
                continue
            w = o.words()
            if w:
                values.append(("|".join(o.names), " ".join(w)))
            elif o.value in FILE_TYPES:
                values.append(("|".join(o.names), None))
        positional_files = any(o.positional and o.value in FILE_TYPES for o in c.options)
        lines.append('      case $prev in')
        for pat, w in values:
            if w is None:
                lines.append(f'        {pat}) compopt -o filenames 2>/dev/null; COMPREPLY=($(compgen -f -- "$cur")); return 0 ;;')
            else:
                lines.append(f'        {pat}) COMPREPLY=($(compgen -W "{w}" -- "$cur"))')
                lines.append('          declare -F __ltrim_colon_completions >/dev/null && __ltrim_colon_completions "$cur"')
                lines.append('          return 0 ;;')
        takes_value = [n for o in c.options if not o.positional and o.value for n in o.names]
        if takes_value:
            lines.append(f'        {"|".join(takes_value)}) return 0 ;;')
        lines.append('      esac')
        if positional_files:
            lines.append('      [[ $cur != -* ]] && { compopt -o filenames 2>/dev/null; COMPREPLY=($(compgen -f -- "$cur")); return 0; }')
        lines.append('      ;;')
    lines += ['    *) return 0 ;;', '  esac',
              '  COMPREPLY=($(compgen -W "$opts" -- "$cur"))',
              "}", "complete -F _bouncer bouncer", ""]
    return "\n".join(lines)


# ---------------------------------------------------------------- main

# ---- API pages: read from the sources, never imported (the docs build needs no built module) ----

def _doc_block(text):
    """A docstring as Markdown: dedented, inside a text block (its layout is columns)."""
    import textwrap
    lines = text.expandtabs().split("\n")
    body = textwrap.dedent("\n".join(lines[1:])) if len(lines) > 1 else ""
    out = (lines[0].strip() + ("\n" + body if body.strip() else "")).strip("\n")
    return "```text\n" + out + "\n```\n"


def python_api_page(src, version):
    """docs/reference/python.md: every public name of the bouncer package (__all__ in
    python/bouncer/__init__.py), its signature and docstring, read with ast from the module
    that defines it (_model.py, _cli.py; _core.pyi for the native types)."""
    import ast
    pkg = os.path.join(src, "python", "bouncer")
    init = ast.parse(open(os.path.join(pkg, "__init__.py"), encoding="utf-8").read())
    public = []
    for node in init.body:
        if isinstance(node, ast.Assign) and any(isinstance(t, ast.Name) and t.id == "__all__" for t in node.targets):
            public = [e.value for e in node.value.elts]
    if not public:
        sys.exit("gen_docs: python/bouncer/__init__.py has no __all__")
    defs = {}
    for mod in ("_model.py", "_cli.py", "_core.pyi"):
        tree = ast.parse(open(os.path.join(pkg, mod), encoding="utf-8").read())
        for node in tree.body:
            if isinstance(node, (ast.FunctionDef, ast.ClassDef)) and node.name not in defs:
                defs[node.name] = (mod, node)
            elif isinstance(node, ast.Assign):
                for t in node.targets:
                    if isinstance(t, ast.Name) and t.id not in defs:
                        defs[t.id] = (mod, node)

    def signature(fn, drop_self):
        a = fn.args
        text = ast.unparse(a)
        if drop_self and text.startswith("self"):
            text = text[len("self"):].lstrip(", ")
        ret = " -> " + ast.unparse(fn.returns) if fn.returns is not None else ""
        return f"{fn.name}({text}){ret}"

    out = [f"# Python API\n\n*Generated from the package's sources by tools/gen_docs.py ({version}).* "
           "Install and the two layers (`bouncer.Model`, typed; the command line in-process): "
           "[From Python](../guide/python.md). Every public name of `bouncer` (`__all__`):\n"]
    # Headings "class Step", "step()", "EVENTS": distinct anchors for the class Step and the
    # function step (MkDocs' toc: lower case, spaces to '-', other punctuation dropped).
    def heading(name):
        if name not in defs:
            sys.exit(f"gen_docs: bouncer.{name} is in __all__ but defined in none of _model.py, _cli.py, _core.pyi")
        node = defs[name][1]
        if isinstance(node, ast.ClassDef):
            return f"class {name}", f"class-{name.lower()}"
        if isinstance(node, ast.FunctionDef):
            return f"{name}()", name.lower()
        return name, name.lower()

    out.append("".join(f"[`{heading(n)[0]}`](#{heading(n)[1]}) " for n in public) + "\n")
    for name in public:
        mod, node = defs[name]
        out.append(f"\n## {heading(name)[0]}\n")
        if isinstance(node, ast.FunctionDef):
            out.append(f"```python\n{signature(node, False)}\n```\n")
            doc = ast.get_docstring(node)
            if doc:
                out.append(_doc_block(doc))
        elif isinstance(node, ast.ClassDef):
            bases = ", ".join(ast.unparse(b) for b in node.bases)
            out.append(f"```python\nclass {name}{'(' + bases + ')' if bases else ''}\n```\n")
            doc = ast.get_docstring(node)
            if doc:
                out.append(_doc_block(doc))
            for m in node.body:
                if isinstance(m, ast.FunctionDef) and not m.name.startswith("_") and ast.get_docstring(m):
                    out.append(f"\n### {name}.{m.name}\n\n```python\n{signature(m, True)}\n```\n")
                    out.append(_doc_block(ast.get_docstring(m)))
        else:
            out.append(f"```python\n{ast.unparse(node)[:300]}\n```\n")
        out.append(f"\n*Defined in* `python/bouncer/{mod}`.\n")
    return "".join(out)


def cpp_api_page(src, version):
    """docs/reference/cpp.md: every public header of the library (lib/include/bouncer), by
    layer: the comment that opens it, with its layout, and its public declarations with their
    comments (tools/cpp_api.py reads them)."""
    return cpp_api.page(src, version)


def write(path, text, written):
    os.makedirs(os.path.dirname(path) or ".", exist_ok=True)
    tmp = path + ".partial"
    with open(tmp, "w", encoding="utf-8") as f:
        f.write(text)
    os.replace(tmp, path)
    written.append(path)


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--bouncer", required=True, help="the built bouncer executable")
    ap.add_argument("--docs", help="docs directory: writes reference/*.md and pictures/*.png into it")
    ap.add_argument("--man", help="directory for bouncer.1 and bouncer-CMD.1")
    ap.add_argument("--completion", help="file for the bash completion script")
    args = ap.parse_args()
    if not (args.docs or args.man or args.completion):
        ap.error("nothing to do: give --docs, --man and/or --completion")
    bouncer = os.path.abspath(args.bouncer)
    v = subprocess.run([bouncer, "--version"], capture_output=True, text=True)
    if v.returncode != 0:
        sys.exit(f"gen_docs: `{bouncer} --version` exited {v.returncode}")
    version = " ".join(v.stdout.split()[:2])  # "bouncer 0.1.0"
    top = parse_help(None, run_help(bouncer, []))
    cmds = [parse_help(n, run_help(bouncer, [n])) for n in commands_of(top.help_text)]
    for c in cmds:
        if not c.usage.startswith(f"bouncer {c.name}"):
            sys.exit(f"gen_docs: the usage line of {c.name} does not start with 'bouncer {c.name}': {c.usage}")

    outputs = {}
    if args.docs:
        ref = os.path.join(args.docs, "reference")
        outputs[os.path.join(ref, "index.md")] = reference_index(top, cmds)
        for c in cmds:
            outputs[os.path.join(ref, c.name + ".md")] = reference_page(c, version)
        src = os.path.join(os.path.dirname(os.path.abspath(__file__)), "..")
        outputs[os.path.join(ref, "python.md")] = python_api_page(src, version)
        outputs[os.path.join(ref, "cpp.md")] = cpp_api_page(src, version)
    if args.man:
        outputs[os.path.join(args.man, "bouncer.1")] = man_page(top, version, cmds)
        for c in cmds:
            outputs[os.path.join(args.man, f"bouncer-{c.name}.1")] = man_page(c, version, cmds)
    if args.completion:
        outputs[args.completion] = completion_script(top, cmds)
    written = []
    for path, text in outputs.items():
        write(path, text, written)
    if args.docs:  # the pictures the pages show (data/pictures/ is their one copy)
        pictures = os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "data", "pictures")
        os.makedirs(os.path.join(args.docs, "pictures"), exist_ok=True)
        for name in sorted(os.listdir(pictures)):
            if name.endswith(".png"):
                shutil.copyfile(os.path.join(pictures, name), os.path.join(args.docs, "pictures", name))
                written.append(name)
    print(f"gen_docs: {len(cmds)} commands, {len(written)} files written")


if __name__ == "__main__":
    main()
