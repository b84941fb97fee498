"""The documentation holds: every Python example of docs/python.md and of the README's
Python section runs, the page names every public attribute of the package, the type
stubs name every attribute of the native classes, and ``mypy --strict`` passes on
``python/examples/``.

Each ```python block runs in a fresh namespace and an empty working folder, in one
interpreter per document (one import of ``ars``), so a block depends on nothing another
block did. ```sh blocks (installs, a Ray cluster, a Slurm job) are not run. A block that
opens a window (``.show(``) runs with the virtual display of ``conftest.display``.
"""

import ast
import json
import os
import re
import subprocess
import sys
import textwrap

from conftest import REPO, window_env

import ars
import ars.gym

DOCS = REPO / "docs" / "python.md"
README = REPO / "README.md"
STUBS = REPO / "python" / "ars" / "_native.pyi"
CLASSES = [ars.Simulation, ars.Body, ars.Joint, ars.Sensor, ars.Renderer]

FENCE = re.compile(r"^```(\w*)\n(.*?)^```", re.DOTALL | re.MULTILINE)


def python_blocks(text, first_line=1):
    """The ```python blocks of ``text``: ``(line of the block's first code line,
    code)``."""
    return [
        (first_line + text.count("\n", 0, m.start(2)), m.group(2))
        for m in FENCE.finditer(text)
        if m.group(1) == "python"
    ]


def readme_python_section():
    """The README's ``## Python`` section and the line it starts on."""
    text = README.read_text()
    start = text.index("\n## Python\n") + 1
    end = text.index("\n## ", start + 1)
    return text[start:end], text.count("\n", 0, start) + 1


RUNNER = textwrap.dedent(
    """
    import json, os, sys, tempfile, traceback

    path, blocks = json.load(sys.stdin)
    failures = []
    for line, code in blocks:
        folder = tempfile.mkdtemp(prefix="ars-doc-block-")
        os.chdir(folder)
        try:
            # Blank lines first: a traceback names the line of the document.
            exec(compile("\\n" * (line - 1) + code, path, "exec"), {"__name__": "__main__"})
        except BaseException:
            failures.append((line, traceback.format_exc()))
    print("RESULT " + json.dumps(failures))
    """
)


def run_blocks(path, blocks, request, tmp_path):
    env = dict(os.environ)
    if any(".show(" in code for _, code in blocks):
        env = window_env(request.getfixturevalue("display"), tmp_path)
    env["TMPDIR"] = str(tmp_path)
    run = subprocess.run(
        [sys.executable, "-c", RUNNER],
        input=json.dumps([str(path), blocks]),
        env=env,
        capture_output=True,
        text=True,
        timeout=300,
        check=False,
    )
    assert run.returncode == 0, run.stderr[-3000:]
    result = [line for line in run.stdout.splitlines() if line.startswith("RESULT ")]
    assert result, run.stdout[-3000:] + run.stderr[-3000:]
    failures = json.loads(result[-1][len("RESULT ") :])
    assert not failures, "\n".join(f"block at line {line}:\n{tb}" for line, tb in failures)


def test_the_python_page_has_examples_of_every_part():
    blocks = python_blocks(DOCS.read_text())
    code = "\n".join(c for _, c in blocks)
    assert len(blocks) >= 20
    # The parts a newcomer reads about each have a block that runs them.
    for call in [
        "load_urdf(",
        "cast_ray(",
        "set_controller(",
        "add_lidar(",
        "add_depth_camera(",
        "set_contact_surface(",
        "Renderer(",
        ".show(",
        "save_scene(",
        "ars.sweep(",
        "class Pendulum(Program)",
        "threading.Thread(",
        "ars.step_many(",
        "(ArsEnv):",
        "gymnasium.make(",
        "ars.gym.make_vec(",
    ]:
        assert call in code, call


def test_every_python_block_of_the_python_page_runs(request, tmp_path):
    run_blocks(DOCS, python_blocks(DOCS.read_text()), request, tmp_path)


def test_every_python_block_of_the_readmes_python_section_runs(request, tmp_path):
    section, line = readme_python_section()
    blocks = python_blocks(section, line)
    assert blocks
    run_blocks(README, blocks, request, tmp_path)


def public(cls):
    return {n for n in dir(cls) if not n.startswith("_")}


def test_the_python_page_names_every_public_attribute():
    text = DOCS.read_text()
    names = set(ars.__all__) - {"__version__"}
    names |= set(ars.gym.__all__)
    for cls in CLASSES:
        names |= public(cls)
    missing = sorted(n for n in names if not re.search(rf"\b{re.escape(n)}\b", text))
    assert not missing, f"docs/python.md does not name: {missing}"


def stub_names():
    """The names the stub defines: at module level, and in each class."""
    tree = ast.parse(STUBS.read_text())
    module, classes = set(), {}

    def defined(body):
        names = set()
        for node in body:
            if isinstance(node, (ast.FunctionDef, ast.ClassDef)):
                names.add(node.name)
            elif isinstance(node, ast.AnnAssign) and isinstance(node.target, ast.Name):
                names.add(node.target.id)
            elif isinstance(node, ast.Assign):
                names |= {t.id for t in node.targets if isinstance(t, ast.Name)}
        return names

    module = defined(tree.body)
    for node in tree.body:
        if isinstance(node, ast.ClassDef):
            classes[node.name] = defined(node.body)
    return module, classes


def test_the_stubs_name_every_attribute_of_the_native_module():
    from ars import _native

    module, classes = stub_names()
    assert {n for n in dir(_native) if not n.startswith("__")} <= module | {"__version__"}
    assert "__version__" in module
    for cls in CLASSES:
        stub = classes[cls.__name__]
        # Public names both ways: nothing missing, nothing the module does not have.
        assert {n for n in stub if not n.startswith("_")} == public(cls), cls.__name__
        # The protocols a class implements itself (len(sensor)).
        protocols = {"__len__", "__iter__", "__getitem__", "__contains__", "__call__"}
        assert protocols & set(vars(cls)) <= stub, cls.__name__
    # Those that can be made are made with the signature the module has.
    assert "__new__" in classes["Simulation"] and "__new__" in classes["Renderer"]


def mypy(request, *paths):
    cache = request.config.cache.mkdir("mypy")
    return subprocess.run(
        [sys.executable, "-m", "mypy", "--strict", "--config-file", "python/pyproject.toml"]
        + ["--cache-dir", str(cache), *map(str, paths)],
        cwd=REPO,
        capture_output=True,
        text=True,
        timeout=600,
        check=False,
    )


def test_mypy_strict_passes_on_the_examples(request):
    examples = sorted((REPO / "python" / "examples").glob("*.py"))
    assert any(p.name == "hello.py" for p in examples)
    run = mypy(request, "python/examples/")
    assert run.returncode == 0, run.stdout + run.stderr
    assert f"no issues found in {len(examples)} source files" in run.stdout


def test_mypy_finds_a_wrong_call_through_the_stubs(request, tmp_path):
    wrong = tmp_path / "wrong.py"
    wrong.write_text(
        "import ars\n"
        "sim = ars.Simulation()\n"
        'sim.add_sphere("big")\n'
        "height: str = sim.body('ball').position\n"
        "sim.joint('j').set_controller('postion', 1.0)\n"
    )
    run = mypy(request, wrong)
    assert run.returncode == 1
    for line in (3, 4, 5):
        assert f"wrong.py:{line}: error" in run.stdout, run.stdout
