"""The wheel is the product: built from a clean copy of the tree, installed (not editable) into a
fresh venv, and used from a folder outside the checkout, CLIs and README snippets included."""

from __future__ import annotations

import importlib.util
import os
import re
import shutil
import subprocess
import sys
import sysconfig
import zipfile
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[2]
HERE = Path(__file__).resolve().parent


def run(*command, cwd: Path, env: dict | None = None, timeout: int = 300) -> str:
    done = subprocess.run(
        [str(part) for part in command], cwd=cwd, env=env, capture_output=True, text=True,
        timeout=timeout,
    )  # fmt: skip
    assert done.returncode == 0, f"{command}\n{done.stdout}\n{done.stderr}"
    return done.stdout + done.stderr


@pytest.fixture(scope="module")
def installed(tmp_path_factory):
    """(wheel, venv python, a work folder outside the checkout, the subprocess environment)."""
    if not (ROOT / ".git").exists():
        pytest.skip("needs a git checkout to copy a clean tree from")
    base = tmp_path_factory.mktemp("wheel")
    tracked = run("git", "ls-files", "-co", "--exclude-standard", cwd=ROOT).split("\n")
    source = base / "source"
    for name in filter(None, tracked):
        if (ROOT / name).is_file():
            (source / name).parent.mkdir(parents=True, exist_ok=True)
            shutil.copy2(ROOT / name, source / name)
    run(sys.executable, "-m", "pip", "wheel", "--no-deps", "-q", source, "-w", base, cwd=base)
    (wheel,) = base.glob("vooga_env-*.whl")
    venv = base / "venv"
    run(sys.executable, "-m", "venv", "--without-pip", venv, cwd=base)
    python = venv / "bin" / "python"
    run(sys.executable, "-m", "pip", "--python", python, "install", "--no-deps", "-q", wheel,
        cwd=base)  # fmt: skip
    # the dependencies come from this env's site-packages, after the venv's own (a .pth line
    # adds a path without running that folder's .pth files: our editable install stays out)
    site = Path(run(python, "-c", "import sysconfig; print(sysconfig.get_paths()['purelib'])",
                    cwd=base).strip())  # fmt: skip
    (site / "dependencies.pth").write_text(sysconfig.get_paths()["purelib"] + "\n")
    work = base / "work"
    work.mkdir()
    env = {k: v for k, v in os.environ.items() if k not in ("PYTHONPATH", "VIRTUAL_ENV")}
    env.update(SDL_VIDEODRIVER="dummy", SDL_AUDIODRIVER="dummy", MPLBACKEND="Agg")
    env["PATH"] = f"{venv / 'bin'}{os.pathsep}{env['PATH']}"
    return wheel, python, site, work, env


def test_the_wheel_holds_the_package_and_every_config_and_nothing_else(installed):
    wheel = installed[0]
    names = set(zipfile.ZipFile(wheel).namelist())
    outside = {n for n in names if not n.startswith(("vooga_env/", "vooga_env-"))}
    assert outside == set(), "only vooga_env/ and its metadata belong in the wheel"
    expected = {f"vooga_env/configs/{p.relative_to(ROOT / 'configs')}"
                for p in (ROOT / "configs").rglob("*.toml")}  # fmt: skip
    expected |= {f"vooga_env/agents/{p.name}" for p in (ROOT / "agents").glob("*.py")}
    expected |= {str(p.relative_to(ROOT)) for p in (ROOT / "vooga_env").rglob("*.py")}
    expected.add("vooga_env/py.typed")
    assert expected - names == set(), "files of the package missing from the wheel"
    assert not any("__pycache__" in n or n.endswith((".nbi", ".nbc")) for n in names)
    entry_points = next(n for n in names if n.endswith("entry_points.txt"))
    commands = zipfile.ZipFile(wheel).read(entry_points).decode()
    for command in ("match", "tournament", "evaluate"):
        assert f"vooga-{command} = vooga_env.agents.{command}:main" in commands
    # these check for their extra first
    for command in ("train", "league", "exploit", "play", "train_rllib"):
        script = command.replace("_", "-")
        assert f"vooga-{script} = vooga_env.agents.cli:{command}" in commands


def test_every_config_and_env_face_works_from_outside_the_checkout(installed):
    _, python, site, work, env = installed
    output = run(python, HERE / "installed_check.py", site, cwd=work, env=env, timeout=600)
    print(output)
    assert "faces ok" in output
    if importlib.util.find_spec("ray") is not None:
        assert "rllib ok" in output
    if "first compiled step" in output and "compiling the fight kernels" not in output:
        pytest.fail("a fresh install compiled without saying so:\n" + output)


def test_the_console_commands_run_and_write_only_where_asked(installed):
    _, _, _, work, env = installed
    folder = work / "cli"
    folder.mkdir()
    temp = work / "temp"
    temp.mkdir()
    env = {**env, "TMPDIR": str(temp)}
    out = run("vooga-match", "rush", "turtle", "--episodes", "2", "--no-progress", cwd=folder,
              env=env)  # fmt: skip
    assert "rush" in out and "turtle" in out
    run("vooga-tournament", "--scripted", "rush", "idle", "--episodes", "1", "--no-progress",
        "--out", "elo.json", cwd=folder, env=env)  # fmt: skip
    run("vooga-train", "--config", "smoke", "--steps", "512", "--out", "run", "--no-progress",
        cwd=folder, env=env, timeout=600)  # fmt: skip
    assert (folder / "run" / "final.zip").exists()
    out = run("vooga-evaluate", "run/final.zip", "--episodes", "2", "--opponents", "rush",
              "--no-progress", cwd=folder, env=env)  # fmt: skip
    assert "rush" in out
    # two leagues, each with its exploiter in another process: all spawned from the console script
    config = work / "parallel.toml"
    smoke = (ROOT / "configs" / "league" / "smoke.toml").read_text()
    smoke = smoke.replace("exploiter_every = 2048", "exploiter_every = 1024")
    config.write_text(smoke.replace("fights = 8", "fights = 8\nleagues = 2")
                      + "exploiter_parallel = true\nselect_games = 2\n")  # fmt: skip
    run("vooga-league", "--config", config, "--steps", "2048", "--out", "league", "--no-progress",
        cwd=folder, env=env, timeout=600)  # fmt: skip
    for league in ("league_0", "league_1"):
        assert (folder / "league" / league / "exploiters" / "exploiter_1024.zip").is_file()
    assert (folder / "league" / "final.zip").is_file()
    assert sorted(p.name for p in folder.iterdir()) == ["elo.json", "league", "run"]
    assert list(temp.glob("SB3-*")) == []  # SB3's learn() makes one without a logger of ours


@pytest.mark.parametrize(
    ("command", "module", "extra"),
    [
        ("vooga-league", "stable_baselines3", "train"),
        ("vooga-exploit", "stable_baselines3", "train"),
        ("vooga-train", "stable_baselines3", "train"),
        ("vooga-train-rllib", "ray", "rllib"),
        ("vooga-play", "pygame", "render"),
    ],
)
def test_a_command_without_its_extra_names_the_extra(installed, command, module, extra):
    """As on a machine that installed the bare wheel: the module the extra brings is not found
    (a `sitecustomize` on the path puts an import hook first that refuses it)."""
    _, _, _, work, env = installed
    missing = work / f"without_{module}"
    missing.mkdir(exist_ok=True)
    (missing / "sitecustomize.py").write_text(
        "import sys\n"
        "class Refuse:\n"
        "    def find_spec(self, name, path=None, target=None):\n"
        f"        if name.split('.')[0] == {module!r}:\n"
        f"            raise ModuleNotFoundError('No module named {module}', name={module!r})\n"
        "sys.meta_path.insert(0, Refuse())\n"
    )
    done = subprocess.run([command, "--help"], cwd=work, env={**env, "PYTHONPATH": str(missing)},
                          capture_output=True, text=True, timeout=120)  # fmt: skip
    assert done.returncode == 1, done.stdout + done.stderr
    assert "Traceback" not in done.stderr
    assert f"no module named '{module}'" in done.stderr
    assert f"pip install 'vooga-env[{extra}]'" in done.stderr


def test_the_readme_python_snippets_run_from_the_wheel(installed):
    _, python, _, work, env = installed
    readme = (ROOT / "README.md").read_text()
    snippets = re.findall(r"```python\n(.*?)```", readme, flags=re.S)
    assert len(snippets) >= 2
    for number, snippet in enumerate(snippets):
        script = work / f"readme_{number}.py"
        script.write_text(snippet)
        run(python, script, cwd=work, env=env, timeout=600)
