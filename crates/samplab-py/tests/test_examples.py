"""Every Python example of the README and the guide runs as shown: each page's ```python
blocks in order, in one namespace per page that starts empty (a page imports what it uses)
but for the reader's own data the text names without making it (an image and its
reference, a stack of them), as the reader would paste them into one session. The shell
examples are run by crates/samplab-cli/tests/examples.rs. A block whose first line is
`# needs a CUDA device` runs only where CuPy finds one (samplab.gpu's)."""

import pathlib
import re

import numpy as np
import pytest

ROOT = pathlib.Path(__file__).resolve().parents[3]
PAGES = [ROOT / "README.md", ROOT / "docs" / "index.md", *sorted((ROOT / "docs" / "guide").glob("*.md"))]


def blocks(text):
    """The ```python blocks of a Markdown text, in order."""
    return re.findall(r"^```python\n(.*?)^```", text, re.S | re.M)


def readers_data():
    """What the guide's examples assume the reader has: renders of one scene (32 x 32 grey
    images), a reference, and a stack of three (frames, or one per sample count)."""
    rng = np.random.default_rng(1)
    reference = rng.random((32, 32))
    noisy = lambda *shape: reference + 0.05 * rng.standard_normal((*shape, 32, 32))
    return {"reference": reference, "image": noisy(), "stack": noisy(3)}


def cuda_device():
    """Whether CuPy is installed and finds a CUDA device."""
    try:
        import cupy

        return cupy.cuda.runtime.getDeviceCount() > 0
    except Exception:
        return False


def test_the_blocks_are_found():
    page = "text\n```python\nx = 1\n```\n```sh\nls\n```\n```python\ny = 2\n```\n"
    assert blocks(page) == ["x = 1\n", "y = 2\n"]
    assert sum(len(blocks(p.read_text())) for p in PAGES) >= 7, "the README and the guide lost their Python examples"


@pytest.mark.parametrize("page", [p for p in PAGES if blocks(p.read_text())], ids=lambda p: p.stem)
def test_every_python_example_runs(page, tmp_path, monkeypatch):
    import dask

    # files the examples write (a checkpoint, a CSV) and a Dask cluster's scratch space go
    # to folders of the test's, not the working folder and /tmp/dask-scratch-space
    monkeypatch.chdir(tmp_path)
    namespace = {"__name__": "__main__", **readers_data()}
    with dask.config.set({"temporary-directory": str(tmp_path / "dask")}):
        for k, code in enumerate(blocks(page.read_text())):
            if code.startswith("# needs a CUDA device") and not cuda_device():
                continue
            exec(compile(code, f"{page.relative_to(ROOT)}, Python block {k + 1}", "exec"), namespace)
