"""The package's floors: each imports only from the floors below it, and no modules import in a
circle (docs/architecture.md). Read from the source's import statements, every one of them
(inside functions and `if TYPE_CHECKING:` too), so a lazy import cannot hide an upward edge."""

from __future__ import annotations

import ast
from pathlib import Path

import pytest

from vooga_env.moved import MOVED

ROOT = Path(__file__).resolve().parent.parent
FLOORS = ("configs", "physics", "game", "kernel", "policies", "envs", "tools", "agents")
# Third-party packages a floor must not import: the engine and the rules run without the RL stack,
# the kernel without gymnasium, and nothing below the tools draws a window except the viewer.
FORBIDDEN = {
    "physics": {"gymnasium", "pettingzoo", "pygame", "numba", "torch", "stable_baselines3", "ray"},
    "game": {"gymnasium", "pettingzoo", "pygame", "numba", "torch", "stable_baselines3", "ray"},
    "kernel": {"gymnasium", "pettingzoo", "pygame", "torch", "stable_baselines3", "ray"},
    "policies": {"gymnasium", "pettingzoo", "pygame", "numba", "ray"},
}


def module_files() -> dict[str, Path]:
    """Every module of the package, by its dotted name (agents/ ships as vooga_env.agents)."""
    files = {}
    for base, package in ((ROOT / "vooga_env", "vooga_env"), (ROOT / "agents", "vooga_env.agents")):
        for path in base.rglob("*.py"):
            parts = list(path.relative_to(base).with_suffix("").parts)
            if parts[-1] == "__init__":
                parts.pop()
            files[".".join([package, *parts])] = path
    return files


MODULES = module_files()


def floor_of(module: str) -> str | None:
    """The floor a module sits on; None for the package root and its alias table (the top)."""
    parts = module.split(".")
    return parts[1] if len(parts) > 1 and parts[1] in FLOORS else None


def imports_of(module: str) -> list[tuple[str, int]]:
    """The modules `module` imports (package-relative imports resolved), with line numbers; a
    `from package import name` counts as importing `package.name` when that is a module."""
    path = MODULES[module]
    package = module if path.name == "__init__.py" else module.rpartition(".")[0]
    found = []
    for node in ast.walk(ast.parse(path.read_text(), str(path))):
        if isinstance(node, ast.Import):
            found += [(alias.name, node.lineno) for alias in node.names]
        elif isinstance(node, ast.ImportFrom):
            base = node.module or ""
            if node.level:
                anchor = package.rsplit(".", node.level - 1)[0] if node.level > 1 else package
                base = f"{anchor}.{base}" if base else anchor
            for alias in node.names:
                name = f"{base}.{alias.name}"
                dunder = alias.name.startswith("__")  # `from vooga_env import __version__`
                found.append((name if name in MODULES or dunder else base, node.lineno))
    return found


def test_every_module_sits_on_a_floor():
    loose = [
        m for m in MODULES if floor_of(m) is None and m not in ("vooga_env", "vooga_env.moved")
    ]
    assert not loose, f"modules outside the floors {FLOORS}: {loose}"


@pytest.mark.parametrize("module", sorted(MODULES))
def test_imports_go_down(module):
    floor = floor_of(module)
    if floor is None:
        return  # the package root registers the envs and aliases the old paths: it is the top
    level = FLOORS.index(floor)
    for name, line in imports_of(module):
        top = name.split(".")[0]
        assert top not in FORBIDDEN.get(floor, ()), (
            f"{module} (floor {floor}) imports {name} at line {line}"
        )
        if top != "vooga_env":
            continue
        assert name not in MOVED, f"{module} imports the old path {name} at line {line}"
        target = floor_of(name)
        assert target is not None or floor == "agents" or name == "vooga_env.__version__", (
            f"{module} imports the package root ({name}) at line {line}: import the module itself"
        )
        if target is not None:
            assert FLOORS.index(target) <= level, (
                f"{module} (floor {floor}) imports {name} (floor {target}) at line {line}"
            )


def test_no_import_cycles():
    graph = {m: {n for n, _ in imports_of(m) if n in MODULES and n != m} for m in MODULES}
    done: set[str] = set()

    def visit(module: str, path: list[str]) -> None:
        if module in path:
            cycle = path[path.index(module) :] + [module]
            raise AssertionError("import cycle: " + " -> ".join(cycle))
        if module in done:
            return
        for target in sorted(graph[module]):
            visit(target, [*path, module])
        done.add(module)

    for module in sorted(graph):
        visit(module, [])


def test_old_paths_still_import_with_a_warning():
    import importlib
    import sys

    for old, new in MOVED.items():
        sys.modules.pop(old, None)
        with pytest.warns(DeprecationWarning) as warned:  # a parent's alias may warn too
            module = importlib.import_module(old)
        assert any(f"{old} moved to {new} " in str(warning.message) for warning in warned)
        assert module is importlib.import_module(new)
        assert module.__spec__.name == new  # so that reload, pickling by spec, -m keep working


def test_the_public_names_of_0_1_still_work():
    import sys

    import vooga_env

    for old in ("vooga_env.vector", "vooga_env.vector.sb3"):
        sys.modules.pop(old, None)
    with pytest.warns(DeprecationWarning):
        from vooga_env.vector import VectorFight
        from vooga_env.vector.sb3 import FightVecEnv
    from vooga_env.kernel import VectorFight as new_vector_fight
    from vooga_env.policies import make_policy

    assert VectorFight is new_vector_fight
    assert FightVecEnv.__module__ == "vooga_env.envs.sb3"
    assert make_policy("rush").name == "rush"
    assert callable(vooga_env.parallel_env) and callable(vooga_env.env)
