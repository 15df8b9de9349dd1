# SPDX-License-Identifier: GPL-3.0-or-later
"""The README's section "Use it from Python" runs as written: its ```python blocks, in
order, in one session, each print giving what its comment says."""
import contextlib
import io
import os
import pathlib
import re

import pytest

README = (pathlib.Path(os.environ.get("PCL_COCONE_SOURCE_DIR",
                                      pathlib.Path(__file__).parents[2]))
          / "README.md")


def section():
    """README.md from its "## Use it from Python" heading to the next "## " heading."""
    text = README.read_text()
    start = text.index("## Use it from Python\n")
    end = text.find("\n## ", start + 1)
    return text[start:] if end < 0 else text[start:end]


def blocks():
    return re.findall(r"^```python\n(.*?)^```", section(), re.S | re.M)


def expected_output(block):
    """The comments of the print lines: `print(...)  # 9996 True`."""
    return "".join(re.search(r"#\s*(.*)$", line).group(1) + "\n"
                   for line in block.splitlines() if line.startswith("print("))


def test_the_first_example_has_five_lines():
    assert len(blocks()[0].strip().splitlines()) == 5


def test_the_python_section_runs_as_written(tmp_path, monkeypatch):
    monkeypatch.chdir(tmp_path)  # where the examples' files go
    session = {}
    for block in blocks():
        if "to_open3d" in block:
            pytest.importorskip("open3d", reason="Open3D is not installed")
        output = io.StringIO()
        with contextlib.redirect_stdout(output):
            exec(compile(block, str(README), "exec"), session)
        assert output.getvalue() == expected_output(block), block
