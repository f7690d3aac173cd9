"""The examples the documentation gives run as written: every ```python block of
docs/python.md, in order, in one namespace, from the repository root; and
tools/examples/fit_fog_with_torch.py, which exits non-zero when its fit misses.
The caller puts the module on PYTHONPATH (ctest does)."""
import os
import pathlib
import re
import subprocess
import sys

import pytest

pytest.importorskip("torch")  # the page's PyTorch examples and the example script need it

REPOSITORY = pathlib.Path(__file__).resolve().parents[2]
PYTHON_BLOCK = re.compile(r"^```python[ \t]*\n(.*?)^```[ \t]*$", re.MULTILINE | re.DOTALL)


def python_blocks(markdown_file):
    """The ```python blocks of a markdown file, in order, each with the line it starts on."""
    text = markdown_file.read_text(encoding="utf-8")
    return [(text.count("\n", 0, match.start(1)) + 1, match.group(1)) for match in PYTHON_BLOCK.finditer(text)]


def test_python_md_has_examples():
    assert len(python_blocks(REPOSITORY / "docs" / "python.md")) >= 5


def test_python_md_examples_run_in_order(monkeypatch):
    monkeypatch.chdir(REPOSITORY)
    document = REPOSITORY / "docs" / "python.md"
    namespace = {"__name__": "docs_python_md"}
    for line, source in python_blocks(document):
        # Compiled under the document's name and padded to its line, so that a
        # traceback points at the line of docs/python.md that failed.
        code = compile("\n" * (line - 1) + source, str(document), "exec")
        exec(code, namespace)


def test_fit_fog_with_torch_recovers_sigma_a(tmp_path):
    # Run from another directory: the script finds the scene from its own location. The
    # caller's PYTHONPATH (build/python, say) is made absolute to hold there too.
    script = REPOSITORY / "tools" / "examples" / "fit_fog_with_torch.py"
    env = dict(os.environ)
    entries = env.get("PYTHONPATH", "").split(os.pathsep)
    env["PYTHONPATH"] = os.pathsep.join(str(pathlib.Path(entry).resolve()) for entry in entries if entry)
    result = subprocess.run([sys.executable, str(script)], cwd=tmp_path, env=env,
                            capture_output=True, text=True, timeout=600)
    assert result.returncode == 0, f"{script} exited with {result.returncode}:\n{result.stdout}\n{result.stderr}"
    assert "recovered sigma_a" in result.stdout
