"""Laminates: plies, layups, 3-D homogenisation and classical lamination theory.

Axes: 1 along the beam (the 0° fibre direction), 2 across the width, 3 through
the thickness. Voigt order (11, 22, 33, 23, 13, 12) with engineering shear
strains. Stiffnesses in Pa, thicknesses in m.

The effective stiffness of a stack (Chou, Carleone & Hsu 1972; Sun & Li 1988;
the paper's ref 11) assumes the in-plane strains (ε11, ε22, γ12) uniform and
the through-thickness stresses (σ33, τ23, τ13) uniform across the plies.
"""

from __future__ import annotations

import math
import re
from dataclasses import dataclass, replace

import numpy as np

from ..errors import InputError
from ..units import INCH

__all__ = [
    "PLANES",
    "Blend",
    "Ply",
    "PlyStrength",
    "STRENGTH_KEYS",
    "PLIES",
    "parse_layup",
    "ply_stiffness",
    "rotate",
    "homogenise",
    "engineering_constants",
    "plane_matrix",
    "abd",
    "Stack",
]

INPLANE = [0, 1, 5]  # 11, 22, 12
OUTPLANE = [2, 3, 4]  # 33, 23, 13


STRENGTH_KEYS = ("Xt", "Xc", "Yt", "Yc", "S", "G_IIc")  # a ply table's strength keys (S23 optional, default S)


@dataclass(frozen=True)
class PlyStrength:
    """Strengths of a ply [Pa]: fibre tension/compression X_t, X_c, transverse Y_t, Y_c,
    in-plane shear S12, transverse shear S23 (Hashin's matrix compression), and the mode-II
    toughness G_IIc [J/m²] of the Davies–Zhang delamination threshold."""

    Xt: float
    Xc: float
    Yt: float
    Yc: float
    S12: float
    S23: float
    GIIc: float
    source: str = "user input"

    def __post_init__(self):
        for k in ("Xt", "Xc", "Yt", "Yc", "S12", "S23", "GIIc"):
            v = getattr(self, k)
            if not (isinstance(v, (int, float)) and math.isfinite(v) and v > 0):
                raise InputError(f"{k} must be positive, got {v!r}", k)


@dataclass(frozen=True)
class Ply:
    """A transversely isotropic or orthotropic ply in its material axes; ``strength`` its
    strengths (None when not given: the damage outputs then refuse it, naming the keys)."""

    name: str
    E1: float
    E2: float
    E3: float
    G12: float
    G13: float
    G23: float
    nu12: float
    nu13: float
    nu23: float
    density: float
    thickness: float
    source: str = "user input"
    strength: PlyStrength | None = None

    def __post_init__(self):
        for k in ("E1", "E2", "E3", "G12", "G13", "G23", "density", "thickness"):
            v = getattr(self, k)
            if not (isinstance(v, (int, float)) and math.isfinite(v) and v > 0):
                raise InputError(f"ply {self.name}: {k} must be positive, got {v!r}")
        try:
            np.linalg.cholesky(ply_stiffness(self))
        except np.linalg.LinAlgError:
            raise InputError(f"ply {self.name}: Poisson ratios {self.nu12}, {self.nu13}, {self.nu23} give a stiffness that is not positive definite") from None


def ply_stiffness(p: Ply) -> np.ndarray:
    """6×6 stiffness of the ply in material axes (inverse of its compliance)."""
    S = np.zeros((6, 6))
    S[0, 0], S[1, 1], S[2, 2] = 1 / p.E1, 1 / p.E2, 1 / p.E3
    S[0, 1] = S[1, 0] = -p.nu12 / p.E1
    S[0, 2] = S[2, 0] = -p.nu13 / p.E1
    S[1, 2] = S[2, 1] = -p.nu23 / p.E2
    S[3, 3], S[4, 4], S[5, 5] = 1 / p.G23, 1 / p.G13, 1 / p.G12
    return np.linalg.inv(S)


MPA = 1e6  # Pa


def _transversely_isotropic(name, E1, E2, G12, nu12, nu23, density, thickness, source, strength) -> Ply:
    """A ply isotropic in its 2–3 plane (E3 = E2, G13 = G12, ν13 = ν12, G23 = E2/(2(1 + ν23)))."""
    return Ply(name, E1, E2, E2, G12, G12, E2 / (2 * (1 + nu23)), nu12, nu12, nu23, density, thickness, source, strength)


# Catalogue provenance (checked 2026-11 against the sources named; every value not found in a
# source says "unverified" in the ply's ``source``). S23 is not tabulated by any source below: the
# catalogue sets S23 = S12 (the transverse-shear stand-in of Hashin's matrix-compression mode).
# G_IIc is tabulated only for IM7/8552 (Camanho et al. 2007); the other values are representative
# of the resin class (brittle 177 °C epoxies 0.5–0.8 kJ/m², glass/epoxy about 1 kJ/m²), unverified.
# Tsai & Hahn's (1980) typical T300/5208 strengths (the T300/5208 entry below), also the stand-in for T300/934.
_T300_5208_STRENGTH = PlyStrength(
    1500 * MPA,
    1500 * MPA,
    40 * MPA,
    246 * MPA,
    68 * MPA,
    68 * MPA,
    500.0,
    "Tsai & Hahn 1980, typical strengths of T300/5208; S23 = S12 assumed; G_IIc 0.5 kJ/m^2 representative, unverified",
)

PLIES = {
    "T300/934": Ply(
        "T300/934",
        120e9,
        7.9e9,
        7.9e9,
        5.5e9,
        5.5e9,
        7.9e9 / (2 * 1.40),
        0.30,
        0.30,
        0.40,
        1580.0,
        0.0055 * INCH,
        "representative literature values (docs/modelling-notes.md); the paper's ref 12 is not available",
        # No T300/934 strength table was found: the T300/5208 strengths of Tsai & Hahn (1980) stand in
        # (same T300 fibre, a 177 °C epoxy), as in the paper report's threshold section.
        replace(
            _T300_5208_STRENGTH,
            source="T300/5208 strengths of Tsai & Hahn 1980 standing in for T300/934; S23 = S12 assumed; G_IIc 0.5 kJ/m^2 representative, unverified",
        ),
    ),
    # Tsai & Hahn (1980), Introduction to Composite Materials, Technomic: the typical unidirectional
    # T300/5208 data (E1 181, E2 10.3, G12 7.17 GPa, nu12 0.28, V_f 0.70; X = X' 1500, Y 40, Y' 246,
    # S 68 MPa). Values confirmed against independent public transcriptions of the book's table (one of
    # them names Martinez & Bishay 2021, Compos. Part C, Table 2, as its copy; that paper itself was not
    # seen); the table number in the book was not confirmed. Density 1600 kg/m³ (rule of mixtures at V_f 0.70 gives 1.6 g/cm³) and ply
    # thickness 0.125 mm are typical, unverified; nu23 0.40 assumed.
    "T300/5208": _transversely_isotropic(
        "T300/5208",
        181e9,
        10.3e9,
        7.17e9,
        0.28,
        0.40,
        1600.0,
        0.125e-3,
        "Tsai & Hahn 1980, typical unidirectional ply data (E1, E2, G12, nu12); density and ply thickness typical, unverified; nu23 assumed 0.40",
        _T300_5208_STRENGTH,
    ),
    # Daniel & Ishai (2006), Engineering Mechanics of Composite Materials, 2nd ed., Oxford UP, table of
    # properties of typical unidirectional composites, AS4/3501-6 row (V_f 0.63, density 1.60 g/cm³,
    # E1 147, E2 10.3, G12 7.0 GPa, nu12 0.27; F1t 2280, F1c 1725, F2t 57, F2c 228, F6 76 MPa):
    # values confirmed against a transcription of that table; its number/appendix not confirmed.
    # (The World-Wide Failure Exercise's AS4/3501-6, Soden, Hinton & Kaddour 1998, is a different
    # batch: E1 126 GPa, X_t 1950 MPa; not mixed in here.) nu23 0.54 is MIL-HDBK-17-3F's AS4/3501-6
    # value (V_f 0.595) as quoted secondhand; ply thickness 0.13 mm typical, unverified.
    "AS4/3501-6": _transversely_isotropic(
        "AS4/3501-6",
        147e9,
        10.3e9,
        7.0e9,
        0.27,
        0.54,
        1600.0,
        0.13e-3,
        "Daniel & Ishai 2006, typical unidirectional properties (AS4/3501-6); nu23 0.54 of MIL-HDBK-17-3F (secondhand); ply thickness typical, unverified",
        PlyStrength(
            2280 * MPA,
            1725 * MPA,
            57 * MPA,
            228 * MPA,
            76 * MPA,
            76 * MPA,
            550.0,
            "Daniel & Ishai 2006 (AS4/3501-6); S23 = S12 assumed; G_IIc 0.55 kJ/m^2 representative, unverified",
        ),
    ),
    # Camanho, Maimí & Dávila (2007), Compos. Sci. Technol. 67, 2715–2727, Table 1 (IM7/8552): E1 171.42,
    # E2 9.08, G12 5.29 GPa, nu12 0.32, X_t 2323.5, X_c 1200.1, Y_t 62.3, Y_c 199.8, S_L 92.3 MPa,
    # G_IIc (G_6) 0.788 kJ/m², cured ply thickness 0.131 mm; confirmed against two transcriptions
    # (NASA CompDam_DGD's IM7-8552.props, which gives X_t 2326.2 MPa, and a published in-situ-strength
    # script, which gives 2323.5). Density 1570 kg/m³ and ply thickness 0.131 mm also in Hexcel's
    # HexPly 8552 data sheet (IM7, nominal laminate density 1.57 g/cm³, cured ply 0.131 mm). nu23 0.52
    # of Camanho, Bessa, Catalanotti, Vogler & Rolfes (2013), Mech. Mater. 59, 36–49, as cited by CompDam.
    "IM7/8552": _transversely_isotropic(
        "IM7/8552",
        171.42e9,
        9.08e9,
        5.29e9,
        0.32,
        0.52,
        1570.0,
        0.131e-3,
        "Camanho, Maimi & Davila 2007, Table 1; Hexcel HexPly 8552 data sheet (density, ply thickness); nu23 of Camanho et al. 2013",
        PlyStrength(
            2323.5 * MPA,
            1200.1 * MPA,
            62.3 * MPA,
            199.8 * MPA,
            92.3 * MPA,
            92.3 * MPA,
            788.0,
            "Camanho, Maimi & Davila 2007, Table 1 (G_IIc = G_6); S23 = S12 assumed",
        ),
    ),
    # Tsai & Hahn (1980): Scotchply 1002 E-glass/epoxy (E1 38.6, E2 8.27, G12 4.14 GPa, nu12 0.26,
    # V_f 0.45; X 1062, X' 610, Y 31, Y' 118, S 72 MPa), confirmed against independent transcriptions;
    # table number not confirmed. Density 1800 kg/m³ (rule of mixtures at V_f 0.45 gives 1.8–1.9 g/cm³)
    # and ply thickness 0.125 mm typical, unverified; nu23 0.40 assumed.
    "E-glass/epoxy": _transversely_isotropic(
        "E-glass/epoxy",
        38.6e9,
        8.27e9,
        4.14e9,
        0.26,
        0.40,
        1800.0,
        0.125e-3,
        "Tsai & Hahn 1980, Scotchply 1002 (E1, E2, G12, nu12); density and ply thickness typical, unverified; nu23 assumed 0.40",
        PlyStrength(
            1062 * MPA,
            610 * MPA,
            31 * MPA,
            118 * MPA,
            72 * MPA,
            72 * MPA,
            1000.0,
            "Tsai & Hahn 1980, typical strengths of Scotchply 1002; S23 = S12 assumed; G_IIc 1 kJ/m^2 representative, unverified",
        ),
    ),
}


def rotate(C: np.ndarray, angle_deg: float) -> np.ndarray:
    """Stiffness of a ply turned by θ about axis 3 (fibres at θ from axis 1)."""
    t = math.radians(angle_deg)
    c, s = math.cos(t), math.sin(t)
    # Stress transformation (Voigt, engineering strains): σ' = T σ, with C' = T⁻¹ C T⁻ᵀ.
    T = np.array(
        [
            [c * c, s * s, 0, 0, 0, 2 * c * s],
            [s * s, c * c, 0, 0, 0, -2 * c * s],
            [0, 0, 1, 0, 0, 0],
            [0, 0, 0, c, -s, 0],
            [0, 0, 0, s, c, 0],
            [-c * s, c * s, 0, 0, 0, c * c - s * s],
        ]
    )
    Ti = np.linalg.inv(T)
    return Ti @ C @ Ti.T


_LAYUP = re.compile(r"^\[(?P<body>[^\]]+)\](?P<count>\d*)(?P<sym>s?)$")
_ITEM = re.compile(r"^(?P<sign>±|\+-|∓|-\+)?(?P<angle>[+-]?\d+(\.\d+)?)(_(?P<n>\d+))?$")


def parse_layup(text: str) -> tuple[float, ...]:
    """Ply angles, top ply first: "[90/0]5s", "[0/±45/90]2s", "[0_2/90]s", "[0/90]".

    ``±45`` is +45 then −45; ``_n`` repeats a ply; a count repeats the group; ``s``
    appends the mirror image.
    """
    compact = str(text).replace(" ", "")
    m = _LAYUP.match(compact)
    if not m:
        raise InputError(f'layup: cannot read {text!r} (expected e.g. "[90/0]5s", "[0/±45/90]2s", "[0_2/90]s")')
    group = []
    for item in m["body"].split("/"):
        im = _ITEM.match(item)
        if not im:
            raise InputError(f"layup: cannot read the ply {item!r} in {text!r}")
        angle = float(im["angle"])
        n = int(im["n"] or 1)
        if n < 1:
            raise InputError(f"layup: repeat count must be >= 1 in {item!r}")
        sign = im["sign"]
        plies = [angle, -angle] if sign in ("±", "+-") else [-angle, angle] if sign in ("∓", "-+") else [angle]
        group += plies * n
    count = int(m["count"] or 1)
    if count < 1:
        raise InputError(f"layup: group count must be >= 1 in {text!r}")
    angles = group * count
    if m["sym"]:
        angles = angles + angles[::-1]
    return tuple(angles)


def homogenise(Cs, fractions) -> np.ndarray:
    """Effective 6×6 stiffness of plies with stiffnesses ``Cs`` and thickness ``fractions``.

    Uniform in-plane strain and uniform out-of-plane stress (module docstring):
    with i the in-plane and o the out-of-plane components and ⟨·⟩ the
    thickness average,
        C*_oo = ⟨C_oo⁻¹⟩⁻¹,  C*_oi = C*_oo ⟨C_oo⁻¹ C_oi⟩,
        C*_ii = ⟨C_ii − C_io C_oo⁻¹ C_oi⟩ + ⟨C_io C_oo⁻¹⟩ C*_oo ⟨C_oo⁻¹ C_oi⟩.
    """
    f = np.asarray(fractions, float)
    if np.any(f < 0) or not math.isclose(f.sum(), 1.0, rel_tol=1e-9):
        raise InputError(f"laminate: ply fractions must be non-negative and add up to 1, got sum {f.sum()!r}")
    i, o = INPLANE, OUTPLANE
    inv_oo = np.zeros((3, 3))
    inv_oo_oi = np.zeros((3, 3))
    io_inv_oo = np.zeros((3, 3))
    schur = np.zeros((3, 3))
    for C, w in zip(Cs, f):
        Coo_inv = np.linalg.inv(C[np.ix_(o, o)])
        Coi, Cio, Cii = C[np.ix_(o, i)], C[np.ix_(i, o)], C[np.ix_(i, i)]
        inv_oo += w * Coo_inv
        inv_oo_oi += w * Coo_inv @ Coi
        io_inv_oo += w * Cio @ Coo_inv
        schur += w * (Cii - Cio @ Coo_inv @ Coi)
    Coo = np.linalg.inv(inv_oo)
    Coi = Coo @ inv_oo_oi
    Cii = schur + io_inv_oo @ Coo @ inv_oo_oi
    out = np.zeros((6, 6))
    out[np.ix_(i, i)] = Cii
    out[np.ix_(o, o)] = Coo
    out[np.ix_(o, i)] = Coi
    out[np.ix_(i, o)] = Coi.T
    return 0.5 * (out + out.T)


def engineering_constants(C: np.ndarray) -> dict[str, float]:
    """E1, E2, E3 [Pa], G23, G13, G12 [Pa], ν12, ν13, ν23 from a 6×6 stiffness."""
    S = np.linalg.inv(C)
    return {
        "E1": 1 / S[0, 0],
        "E2": 1 / S[1, 1],
        "E3": 1 / S[2, 2],
        "G23": 1 / S[3, 3],
        "G13": 1 / S[4, 4],
        "G12": 1 / S[5, 5],
        "nu12": -S[0, 1] / S[0, 0],
        "nu13": -S[0, 2] / S[0, 0],
        "nu23": -S[1, 2] / S[1, 1],
    }


PLANES = ("strain", "stress")  # the beam's plane assumption across its width


def plane_matrix(C: np.ndarray, plane: str = "strain") -> np.ndarray:
    """3×3 matrix of the axis–thickness plane, (σ11, σ33, τ13) = D·(ε11, ε33, γ13).

    ``strain``: plane strain across the width (ε22 = γ12 = γ23 = 0), the paper's
    elements; ``stress``: plane stress (σ22 = τ12 = τ23 = 0), for a narrow beam.
    """
    keep = [0, 2, 4]
    if plane == "strain":
        return C[np.ix_(keep, keep)].copy()
    if plane == "stress":
        return np.linalg.inv(np.linalg.inv(C)[np.ix_(keep, keep)])
    raise InputError(f"plane: {plane!r} is not one of {', '.join(PLANES)}", "plane")


def reduced_stiffness(C: np.ndarray) -> np.ndarray:
    """Plane-stress reduced stiffness Q (11, 22, 12) of a ply: σ33 = τ23 = τ13 = 0."""
    return np.linalg.inv(np.linalg.inv(C)[np.ix_(INPLANE, INPLANE)])


def abd(Cs, thicknesses) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """Classical lamination theory: A, B, D (3×3 each, per unit width), plies top first.

    z is measured up from the mid-plane; the top ply lies at z = +h/2.
    """
    t = np.asarray(thicknesses, float)
    h = t.sum()
    tops = h / 2 - np.concatenate(([0.0], np.cumsum(t)[:-1]))
    bottoms = tops - t
    A, B, D = np.zeros((3, 3)), np.zeros((3, 3)), np.zeros((3, 3))
    for C, zt, zb in zip(Cs, tops, bottoms):
        Q = reduced_stiffness(C)
        A += Q * (zt - zb)
        B += Q * (zt**2 - zb**2) / 2
        D += Q * (zt**3 - zb**3) / 3
    return A, B, D


@dataclass(frozen=True)
class Stack:
    """A laminate: its ply material and angles (top ply first)."""

    ply: Ply
    angles: tuple[float, ...]

    @property
    def thickness(self) -> float:
        return self.ply.thickness * len(self.angles)

    def ply_stiffnesses(self) -> list[np.ndarray]:
        C = ply_stiffness(self.ply)
        return [rotate(C, a) for a in self.angles]

    def effective(self) -> np.ndarray:
        """Smeared 6×6 stiffness of the whole stack."""
        n = len(self.angles)
        return homogenise(self.ply_stiffnesses(), np.full(n, 1.0 / n))

    def layer_stiffness(self, z_lo: float, z_hi: float) -> np.ndarray:
        """Smeared stiffness of the part of the stack between heights z_lo < z_hi,
        measured up from the bottom face (for the layered model)."""
        tp = self.ply.thickness
        Cs, w = [], []
        for k, C in enumerate(self.ply_stiffnesses()):
            top = self.thickness - k * tp
            overlap = min(top, z_hi) - max(top - tp, z_lo)
            if overlap > 1e-15 * tp:
                Cs.append(C)
                w.append(overlap)
        w = np.asarray(w)
        return homogenise(Cs, w / w.sum())

    def bending_stiffness(self, plane: str = "strain") -> dict[str, float]:
        """Bending stiffness per unit width [N·m]: the smeared model's E·h³/12 against CLT's D11."""
        D_sm = plane_matrix(self.effective(), plane)
        E_beam = 1.0 / np.linalg.inv(D_sm)[0, 0]  # σ33 = τ13 = 0 in the beam
        h = self.thickness
        _, _, D = abd(self.ply_stiffnesses(), [self.ply.thickness] * len(self.angles))
        d11 = 1.0 / np.linalg.inv(D)[0, 0] if plane == "stress" else D[0, 0]
        return {
            "smeared_EI_per_width": E_beam * h**3 / 12,
            "clt_D11": float(D[0, 0]),
            "clt_1_over_d11": float(1 / np.linalg.inv(D)[0, 0]),
            "clt_beam": float(d11),
        }


@dataclass(frozen=True)
class Blend:
    """A laminate known only by the thickness fractions of its ply angles (no stacking
    order): enough for the smeared stiffness, not for the layered model or CLT bending."""

    ply: Ply
    fractions: tuple[tuple[float, float], ...]  # (angle, fraction)
    total_thickness: float

    def __post_init__(self):
        f = np.array([w for _, w in self.fractions])
        if np.any(f < 0) or not math.isclose(f.sum(), 1.0, rel_tol=1e-6):
            raise InputError(f"fractions must be non-negative and add up to 1, got {f.sum():.6g}", "fractions")
        if not self.total_thickness > 0:
            raise InputError(f"thickness must be positive, got {self.total_thickness!r}", "thickness")

    @property
    def thickness(self) -> float:
        return self.total_thickness

    def effective(self) -> np.ndarray:
        C = ply_stiffness(self.ply)
        return homogenise([rotate(C, a) for a, _ in self.fractions], [w for _, w in self.fractions])

    def layer_stiffness(self, z_lo, z_hi):
        raise InputError("'layered' needs a layup (stacking order), not fractions", "model")

    def bending_stiffness(self, plane: str = "strain") -> dict[str, float]:
        E_beam = 1.0 / np.linalg.inv(plane_matrix(self.effective(), plane))[0, 0]
        return {"smeared_EI_per_width": E_beam * self.thickness**3 / 12}
