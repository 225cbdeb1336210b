"""The fit of the contact law's X2^n (Eqs. 16-17): the spec of generated/fit.py."""

from __future__ import annotations

from .. import fit as ft
from .. import laws, mdsm
from ..codegen import FunctionSpec, ModuleSpec
from ._shared import (
    CONTACT,
    _per,
)

__all__ = ["build"]


def build() -> ModuleSpec:
    """Eqs. (16)-(17): the least-squares polynomial of the contact law's X2^n, exact errors."""
    options = CONTACT + (("degree", "int, 1 to 8", 3, "polynomial degree; 3 gives Eq. (17)"),)
    arg = (ft.X2max,)
    docs = {"X2max": "upper end of the fitted range [0, X2max] [m]"}

    def per_degree(build):
        return {(c, n): build(n, c) for c in laws.choices("contact") for n in ft.DEGREES}

    endpoints = (
        "For a symbolic exponent (hunt_crossley) the larger of the errors at X2 = 0 and at "
        "X2max, closed forms in n_h: an interior extremum of X2^n_h - fit has no closed "
        "form (the tests check against a dense scan that none is larger)."
    )
    functions = (
        FunctionSpec(
            "coefficients",
            "Coefficients (c0, ..., c_degree) of the L2 fit of X2^n.",
            "Eqs. (16)-(17)",
            "tuple",
            "c : tuple of ndarray\n    X2^n ~ sum_k c_k X2^k on [0, X2max], n the contact "
            "law's exponent\n    (3/2: Eq. 17).",
            per_degree(lambda n, c: list(ft.coefficients_eq_17(n, c))),
            options,
            arg,
            docs,
            notes="Rational functions of the exponent times powers of X2max, from the "
            "continuous normal equations (Hilbert matrix) solved by SymPy; exact "
            "rationals for Eq. (1).",
            examples=(
                "Eq. (17) on [0, 1]: c0 = -8/1155; Kelvin-Voigt's X2^1 is fitted exactly:\n"
                "\n"
                ">>> from beltmdsm.generated import fit\n"
                ">>> [round(float(c), 4) for c in fit.coefficients(1.0)]\n"
                "[-0.0069, 0.3117, 0.9351, -0.2424]\n"
                '>>> [float(c) for c in fit.coefficients(1.0, contact="kelvin_voigt")]\n'
                "[0.0, 1.0, 0.0, 0.0]"
            ),
        ),
        FunctionSpec(
            "max_error",
            "Largest absolute error of the fit on [0, X2max], exact.",
            "Eq. (17) (the paper: 'about 1e-2')",
            "value",
            "err : ndarray\n    max |X2^n - fit| (for Eq. 1, degree 3: 8/1155 X2max^(3/2)).",
            per_degree(lambda n, c: ft.fit_error(n, c).max_abs),
            options,
            arg,
            docs,
            notes=endpoints,
            examples=(
                "Degree 3 for Eq. (1): 8/1155 X2max^(3/2):\n"
                "\n"
                ">>> from beltmdsm.generated import fit\n"
                ">>> round(float(fit.max_error(4.0)), 6), round(8 / 1155 * 4.0**1.5, 6)\n"
                "(0.055411, 0.055411)"
            ),
        ),
        FunctionSpec(
            "max_error_location",
            "Where the largest error of the fit sits.",
            "Eq. (17)",
            "value",
            "X2 : ndarray",
            per_degree(lambda n, c: ft.fit_error(n, c).argmax),
            options,
            arg,
            docs,
            notes=endpoints,
            examples=(
                "For Eq. (17) the largest error sits at X2 = 0, where it is |c0|:\n"
                "\n"
                ">>> from beltmdsm.generated import fit\n"
                ">>> float(fit.max_error_location(1.0))\n"
                "0.0"
            ),
        ),
        FunctionSpec(
            "rms_error",
            "Root-mean-square error of the fit on [0, X2max], exact.",
            "Eq. (17)",
            "value",
            "rms : ndarray",
            per_degree(lambda n, c: ft.fit_error(n, c).rms),
            options,
            arg,
            docs,
            notes="From the normal equations: the mean square error is "
            "X2max^(2n) (1/(2n+1) - sum_k d_k/(k+n+1)), a closed form in n.",
            examples=(
                "Against the mean square error on a dense grid of [0, 1]:\n"
                "\n"
                ">>> from beltmdsm.generated import fit\n"
                ">>> import numpy as np\n"
                ">>> x = np.linspace(0.0, 1.0, 200001)\n"
                ">>> c = fit.coefficients(1.0)\n"
                ">>> err = x**1.5 - sum(ck * x**k for k, ck in enumerate(c))\n"
                ">>> rms = np.sqrt(np.mean(err**2))\n"
                ">>> round(float(fit.rms_error(1.0)), 6), round(float(rms), 6)\n"
                "(0.001299, 0.001299)"
            ),
        ),
        FunctionSpec(
            "mdsm_fit_range",
            "The fitted range for the MDSM: X2^0 plus the fast normal amplitude.",
            "Eqs. (9), (14), (16)",
            "value",
            "X2max : ndarray",
            _per(mdsm.x2max, "contact"),
            CONTACT,
            notes="The fast normal motion is the linear response of the normal block "
            "of Eq. (11) to the normal excitation; X2^0 and the block are those of "
            "the contact law whose power `coefficients` fits.",
            examples=(
                "Without excitation (alpha = 0) it is the equilibrium penetration X2^0:\n"
                "\n"
                ">>> from beltmdsm.generated import fit, unforced\n"
                ">>> from beltmdsm.generated.parameters import BASE\n"
                ">>> round(float(fit.mdsm_fit_range(**BASE)), 4)\n"
                "12.6998\n"
                '>>> calm = {**BASE, "alpha": 0.0}\n'
                ">>> X2 = unforced.equilibrium(**calm)[2]\n"
                ">>> round(float(fit.mdsm_fit_range(**calm)), 4), round(float(X2), 4)\n"
                "(11.5474, 11.5474)"
            ),
        ),
    )
    return ModuleSpec(
        "fit",
        """Least-squares polynomial fit of the contact law's power X2^n on [0, X2max] (Eqs. 16-17).

Degrees 1 to 8, exact in X2max and in the exponent (``contact=``: 3/2 for Eq. 1, the
symbol ``n_h`` of Hunt-Crossley's law; the linear law's fit is exact). ``X2max`` comes
from the scene (for the MDSM: the slow penetration plus the amplitude of the fast
normal motion, `mdsm_fit_range` of the same contact law), not a constant.
""",
        functions,
    )
