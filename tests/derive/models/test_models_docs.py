"""The models' documentation (issue 39 item 6): the how-to's worked example registers a
model that derives, and the reference page lists every model with its parameters."""

import importlib.util
import re
import subprocess
import sys
from pathlib import Path

from beltmdsm.generated.models import MODELS, load

ROOT = Path(__file__).resolve().parents[3]
HOWTO = ROOT / "docs" / "howto" / "own_model.md"


def test_the_worked_example_registers_a_model_that_derives():
    """The how-to's entry, run where it says to put it (the namespace of
    derive/models/entries.py), registers; its generated module finds steady sliding
    (the cubic spring's residual vanishes) and its Hurwitz determinants are positive."""
    blocks = re.findall(r"```python\n(.*?)```", HOWTO.read_text(encoding="utf-8"), re.S)
    entry_code, use_code = blocks[0], blocks[1]
    assert 'register(\n    "model",' in entry_code
    script = "\n".join(
        [
            "import numpy as np",
            "from beltmdsm.derive.models import entries",
            "from beltmdsm.derive.models.render import render_model",
            "ns = vars(entries)",
            f"exec({entry_code!r}, ns)",
            "module = {'__name__': 'duffing_belt'}",
            "exec(render_model('duffing_belt'), module)",
            "load = lambda name: type('M', (), module)",
            f"exec({use_code.replace('from beltmdsm.generated.models import load', '')!r})",
            "d = m.DEFAULTS",
            "x = y0[0]",
            "mu = d['mu_k'] + (d['mu_s'] - d['mu_k']) * np.exp(-d['Vb'] / d['v_s'])",
            "residual = d['omega1']**2 * x + d['k3'] * x**3 - mu * d['g']",
            "assert abs(residual) <= 1e-13 * mu * d['g'], residual",
            "assert np.all(k.hurwitz(p) > 0)",
            "print(m.EQUILIBRIUM['stribeck'].split(':')[0])",
        ]
    )
    out = subprocess.run(
        [sys.executable, "-c", script], capture_output=True, text=True, cwd=ROOT, timeout=300
    )
    assert out.returncode == 0, out.stderr[-2000:]
    assert out.stdout.strip() == "numeric"  # as the page says


def _site():
    spec = importlib.util.spec_from_file_location(
        "beltmdsm_site", ROOT / "docs" / "_ext" / "beltmdsm_site.py"
    )
    module = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(module)
    return module


def test_the_models_page_lists_every_model_and_parameter():
    page = _site().models_page()
    sections = re.split(r"\n``(\w+)``(?: \(default\))?\n-+\n", page)
    names = sections[1::2]
    assert tuple(names) == MODELS and "``paper`` (default)" in page
    for name, body in zip(names, sections[2::2]):
        m = load(name)
        for parameter, default in m.DEFAULTS.items():
            assert f"   * - ``{parameter}``\n     - " in body, (name, parameter)
            assert f"     - {default:g}\n" in body
        for state in m.STATES:
            assert f"``{state}``" in body
        assert ("unilateral" in body) == m.UNILATERAL


def test_the_entry_examples_run():
    import doctest
    import importlib

    for name in ("entry", "registry"):
        module = importlib.import_module(f"beltmdsm.derive.models.{name}")
        result = doctest.testmod(module)
        assert result.attempted > 0 and result.failed == 0, (name, result)
