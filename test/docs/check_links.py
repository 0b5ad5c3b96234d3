#!/usr/bin/env python3
"""Checks that the documentation points at things that exist.

Reads README.md, every docs/**/*.md and CHANGELOG.rst of the package and fails (exit 1, one line per
problem) when
  - a relative link or image does not resolve (in CHANGELOG.rst: `text <target>`_ and .. image::): the file or folder must exist inside the package, and a
    #anchor must be a heading of the target page (GitHub's rule: lowercase, spaces to '-', punctuation
    dropped, a repeated heading gets -1, -2, ...);
  - `roslaunch costmap_layers FILE` names a file that is not in launch/, or passes an argument
    (`name:=value`) that the launch file does not declare;
  - `rosrun costmap_layers PROGRAM` names a program CMakeLists.txt does not install;
  - a path in inline code (``literal`` in reStructuredText) that starts with one of the package's folders (`scripts/demo.sh`,
    `params/costmap_example.yaml`, ...) does not exist;
  - a plugin of gradient_plugins.xml has no page docs/plugins/<Class>.md, or README.md does not link it.
Web links are not followed. Deterministic, no network, standard library only.

Usage: check_links.py [ROOT] [--readme FILE]
  ROOT      the package folder (default: two folders above this script)
  --readme  check FILE as if it were ROOT/README.md (e.g. a README.new.md before it replaces README.md)
"""
import argparse
import glob
import os
import re
import sys
import urllib.parse

FENCE = re.compile(r"^\s*(```|~~~)")
HEADING = re.compile(r"^(#{1,6})\s+(.*?)\s*#*\s*$")
LINK = re.compile(r"!?\[(?:[^\[\]]|\[[^\[\]]*\])*\]\(\s*<?([^)\s>]*)>?(?:\s+\"[^\"]*\")?\s*\)")
HTML_REF = re.compile(r"<(?:a|img)\s[^>]*?(?:href|src)=\"([^\"]+)\"", re.IGNORECASE)
HTML_ANCHOR = re.compile(r"<a\s[^>]*?(?:name|id)=\"([^\"]+)\"", re.IGNORECASE)
INLINE_CODE = re.compile(r"(`+)(.+?)\1", re.DOTALL)
RST_LINK = re.compile(r"`[^`<]*<([^<>`]+)>`__?")
RST_IMAGE = re.compile(r"^\s*\.\.\s+(?:image|figure)::\s*(\S+)")
RST_LITERAL = re.compile(r"``(.+?)``")
ROSLAUNCH = re.compile(r"roslaunch\s+(?:--?\S+\s+)*costmap_layers\s+([^\s`]+)([^\n`]*)")
ROSRUN = re.compile(r"rosrun\s+costmap_layers\s+([^\s`]+)")
LAUNCH_ARG = re.compile(r"<arg\s[^>]*?name=\"([^\"]+)\"")
# Inline-code tokens starting with one of these are paths in the package.
PACKAGE_FOLDERS = ("scripts/", "params/", "launch/", "example/", "test/", "include/", "src/", "bench/",
                   "docs/", "cmake/", "msg/", "srv/")


def slug(text):
    """GitHub's anchor for a heading's text."""
    text = re.sub(r"!?\[([^\]]*)\]\([^)]*\)", r"\1", text)  # a link counts as its text
    text = text.replace("`", "").replace("*", "")
    text = re.sub(r"<[^>]+>", "", text)  # inline HTML
    text = text.strip().lower()
    text = "".join(c for c in text if c.isalnum() or c in " -_")
    return text.replace(" ", "-")


def prose_lines(text):
    """(line number, line) outside fenced code blocks."""
    in_fence = False
    for number, line in enumerate(text.splitlines(), 1):
        if FENCE.match(line):
            in_fence = not in_fence
            continue
        if not in_fence:
            yield number, line


def anchors_of(text):
    seen = {}
    anchors = set()
    for _, line in prose_lines(text):
        m = HEADING.match(line)
        if m:
            base = slug(m.group(2))
            count = seen.get(base, 0)
            seen[base] = count + 1
            anchors.add(base if count == 0 else f"{base}-{count}")
        anchors.update(HTML_ANCHOR.findall(line))
    return anchors


def joined_lines(text):
    """(line number, line) with shell continuations ('\\' at the end) joined, code blocks included."""
    lines = text.splitlines()
    i = 0
    while i < len(lines):
        start, line = i + 1, lines[i]
        while line.rstrip().endswith("\\") and i + 1 < len(lines):
            i += 1
            line = line.rstrip()[:-1] + " " + lines[i].strip()
        yield start, line
        i += 1


def installed_programs(root):
    with open(os.path.join(root, "CMakeLists.txt"), encoding="utf-8") as f:
        cmake = re.sub(r"#[^\n]*", "", f.read())
    programs = set()
    for body in re.findall(r"install\s*\(\s*TARGETS([^)]*?)RUNTIME\s+DESTINATION\s+\$\{CATKIN_PACKAGE_BIN_DESTINATION\}",
                           cmake):
        programs.update(body.split())
    for body in re.findall(r"catkin_install_python\s*\(\s*PROGRAMS([^)]*?)DESTINATION", cmake):
        programs.update(os.path.basename(p) for p in body.split())
    return programs


def plugin_classes(root):
    with open(os.path.join(root, "gradient_plugins.xml"), encoding="utf-8") as f:
        return sorted(re.findall(r"<class\s+name=\"costmap_layers/([A-Za-z0-9_]+)\"", f.read()))


class Checker:
    def __init__(self, root, readme):
        self.root = os.path.realpath(root)
        self.readme = os.path.realpath(readme) if readme else os.path.join(self.root, "README.md")
        self.problems = []
        self.texts = {}
        self.programs = installed_programs(self.root)

    def text(self, path):
        """The text of a page by its place in the package (README.md maps to --readme)."""
        if path not in self.texts:
            source = self.readme if path == os.path.join(self.root, "README.md") else path
            with open(source, encoding="utf-8") as f:
                self.texts[path] = f.read()
        return self.texts[path]

    def problem(self, path, number, message):
        self.problems.append(f"{os.path.relpath(path, self.root)}:{number}: {message}")

    def pages(self):
        pages = [os.path.join(self.root, "README.md")]
        pages += sorted(glob.glob(os.path.join(self.root, "docs", "**", "*.md"), recursive=True))
        changelog = os.path.join(self.root, "CHANGELOG.rst")
        return pages + ([changelog] if os.path.isfile(changelog) else [])

    def check_link(self, page, number, target):
        if re.match(r"^[a-z][a-z0-9+.-]*:", target, re.IGNORECASE):  # http:, https:, mailto:
            return
        path_part, _, anchor = target.partition("#")
        path_part = urllib.parse.unquote(path_part)
        if path_part:
            resolved = os.path.realpath(os.path.join(os.path.dirname(page), path_part))
            if os.path.commonpath([resolved, self.root]) != self.root:
                self.problem(page, number, f"link '{target}' leaves the package")
                return
            if not os.path.exists(resolved):
                self.problem(page, number, f"link '{target}': {os.path.relpath(resolved, self.root)} does not exist")
                return
        else:
            resolved = page
        if anchor:
            if not resolved.endswith(".md") or os.path.isdir(resolved):
                self.problem(page, number, f"link '{target}': an anchor into a file that is not a Markdown page")
                return
            if anchor not in anchors_of(self.text(resolved)):
                self.problem(page, number,
                             f"link '{target}': no heading '#{anchor}' in {os.path.relpath(resolved, self.root)}")

    def check_code(self, page, number, code):
        """Package paths in a piece of inline code exist."""
        for token in re.split(r"[\s=]+", code):
            token = token.strip("()[],;:'\"")
            if not token.startswith(PACKAGE_FOLDERS) or re.search(r"[<>{}$]|\.\.\.", token):
                continue
            matches = glob.glob(os.path.join(self.root, token)) if "*" in token else \
                [os.path.join(self.root, token)] if os.path.exists(os.path.join(self.root, token)) else []
            if not matches:
                self.problem(page, number, f"path '{token}' does not exist in the package")

    def check_rst_page(self, page):
        """CHANGELOG.rst: links, images and ``literal`` package paths (it has no code blocks to skip)."""
        for number, line in enumerate(self.text(page).splitlines(), 1):
            for target in RST_LINK.findall(line) + RST_IMAGE.findall(line):
                self.check_link(page, number, target)
            for code in RST_LITERAL.findall(line):
                self.check_code(page, number, code)

    def check_page(self, page):
        text = self.text(page)
        if page.endswith(".rst"):
            self.check_rst_page(page)
        for number, line in (() if page.endswith(".rst") else prose_lines(text)):
            without_code = INLINE_CODE.sub("", line)
            for target in LINK.findall(without_code) + HTML_REF.findall(without_code):
                self.check_link(page, number, target)
            for _, code in INLINE_CODE.findall(line):
                self.check_code(page, number, code)
        for number, line in joined_lines(text):
            for name, rest in ROSLAUNCH.findall(line):
                if "<" in name:
                    continue
                launch = os.path.join(self.root, "launch", name)
                if not os.path.isfile(launch):
                    self.problem(page, number, f"roslaunch costmap_layers {name}: no such file in launch/")
                    continue
                with open(launch, encoding="utf-8") as f:
                    declared = set(LAUNCH_ARG.findall(f.read()))
                for token in rest.split():
                    m = re.match(r"^\[?([A-Za-z_][A-Za-z0-9_]*):=", token)
                    if not m:
                        break
                    if m.group(1) not in declared:
                        self.problem(page, number, f"roslaunch costmap_layers {name}: no argument '{m.group(1)}' "
                                     f"(declared: {', '.join(sorted(declared))})")
            for program in ROSRUN.findall(line):
                if "<" in program:
                    continue
                if program not in self.programs:
                    self.problem(page, number, f"rosrun costmap_layers {program}: CMakeLists.txt installs no such "
                                 f"program (installed: {', '.join(sorted(self.programs))})")

    def check_plugins(self):
        readme = os.path.join(self.root, "README.md")
        linked = set()
        for _, line in prose_lines(self.text(readme)):
            for target in LINK.findall(INLINE_CODE.sub("", line)):
                linked.add(os.path.normpath(target.partition("#")[0]))
        for name in plugin_classes(self.root):
            page = os.path.join("docs", "plugins", name + ".md")
            if not os.path.isfile(os.path.join(self.root, page)):
                self.problem(os.path.join(self.root, "gradient_plugins.xml"), 0,
                             f"costmap_layers/{name} has no page {page}")
            elif page not in linked:
                self.problem(readme, 0, f"the plugin table does not link {page}")

    def run(self):
        for page in self.pages():
            self.check_page(page)
        self.check_plugins()
        return self.problems


def main(argv):
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("root", nargs="?", default=os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", ".."))
    parser.add_argument("--readme", help="check this file in place of ROOT/README.md")
    args = parser.parse_args(argv)
    checker = Checker(args.root, args.readme)
    problems = checker.run()
    for p in problems:
        print(f"check_links: {p}")
    print(f"check_links: {len(checker.pages())} pages, {len(problems)} problems")
    return 1 if problems else 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
