#!/usr/bin/python3
"""Checks that the README's examples are the files ctest runs (ctest: readme_examples).

Each C++, Python or JavaScript code block of README.md that is followed by a line
"This is `examples/...`" must be that file, verbatim, after the file's own header (leading
comment lines, a shebang, a module docstring), which the README leaves out. ctest builds and runs
those files (example_cpp_quickstart, python_example_quickstart, example_js_quickstart), so an
example in the README that no longer compiles or runs fails a test either way.
Fails (exit 1, one line per problem) when a block and its file differ, a named file is missing,
or fewer than the three examples (C++, Python, JavaScript) are found.
Usage: scripts/check-readme-examples.py [repository root]
"""
import ast
import pathlib
import re
import sys

ROOT = pathlib.Path(sys.argv[1] if len(sys.argv) > 1 else pathlib.Path(__file__).parent.parent)
BLOCK_RE = re.compile(r"^```(cpp|python|js)\n(.*?)^```\n\s*This is `(examples/[^`]+)`",
                      re.S | re.M)


def header_only(prefix, language):
    """Whether `prefix` (the file before the README's block) is only a header, no code."""
    if language == "python":
        lines = prefix.splitlines()
        if lines and lines[0].startswith("#!"):
            lines = lines[1:]
        text = "\n".join(lines).strip()
        if not text:
            return True
        try:
            body = ast.parse(text).body
        except SyntaxError:
            return False
        return len(body) == 1 and isinstance(body[0], ast.Expr) and isinstance(
            getattr(body[0], "value", None), ast.Constant) and isinstance(body[0].value.value, str)
    return all(not line.strip() or line.lstrip().startswith("//") for line in prefix.splitlines())


def main():
    readme = (ROOT / "README.md").read_text()
    problems = []
    found = set()
    for language, block, path in BLOCK_RE.findall(readme):
        file = ROOT / path
        if not file.is_file():
            problems.append(f"README.md: {path} does not exist")
            continue
        text = file.read_text()
        if not text.endswith(block):
            problems.append(f"README.md: the {language} block differs from the end of {path}")
        elif not header_only(text[:len(text) - len(block)], language):
            problems.append(f"README.md: {path} has code before the part the README shows")
        else:
            found.add(language)
    missing = {"cpp", "python", "js"} - found
    if missing:
        problems.append("README.md: no checked example in " + ", ".join(sorted(missing)))
    for line in problems:
        print(line)
    if problems:
        return 1
    print("check-readme-examples: the README's C++, Python and JavaScript examples are "
          "their files")
    return 0


if __name__ == "__main__":
    sys.exit(main())
