"""Catalogue plies: each ply's constants and strengths are physically consistent with each other and
with its constituents (issue 21 item 4). The expected ranges and constituent data below come from
physics and from the sources named, never from the catalogue itself."""

import numpy as np
import pytest

from softimpact.models.laminate import PLIES, ply_stiffness

NAMES = sorted(PLIES)

# Fibre volume fraction and constituent densities [kg/m³] of each ply, from the sources named:
# V_f of T300/5208 and Scotchply 1002 from Tsai & Hahn (1980), of AS4/3501-6 from Daniel & Ishai (2006),
# of IM7/8552 from Hexcel's HexPly 8552 data sheet (57.70 %); fibre densities T300 1760 (Toray T300 data
# sheet), AS4 1790 and IM7 1770 (HexPly 8552 data sheet), E-glass 2540–2600 (handbook range, 2570 used);
# resin 8552 1300 (HexPly 8552 data sheet), other cured epoxies 1200–1300 (1250 used). T300/934's V_f is
# not known (None): its density must then imply a V_f of an autoclaved prepreg, 0.5–0.75.
CONSTITUENTS = {
    "T300/934": (None, 1760.0, 1250.0),
    "T300/5208": (0.70, 1760.0, 1250.0),
    "AS4/3501-6": (0.63, 1790.0, 1250.0),
    "IM7/8552": (0.577, 1770.0, 1300.0),
    "E-glass/epoxy": (0.45, 2570.0, 1250.0),
}


def test_constituent_table_covers_the_catalogue():
    """Every catalogue ply has its constituent data in this test, so none escapes the checks below."""
    assert set(CONSTITUENTS) == set(PLIES)


@pytest.mark.parametrize("name", NAMES)
def test_strength_ratios_are_physical(name):
    """Strength ratios lie where fibre-dominated unidirectional plies put them: fibre compression below or
    near fibre tension (kinking), transverse compression 2–7 times transverse tension, the fibre direction
    at least ten times the transverse one, and the in-plane shear strength between 1 and 3 times Y_t."""
    x = PLIES[name].strength
    assert 0.3 <= x.Xc / x.Xt <= 1.1
    assert 2.0 <= x.Yc / x.Yt <= 7.0
    assert x.Xt / x.Yt >= 10.0
    assert 1.0 <= x.S12 / x.Yt <= 3.0
    assert x.S23 <= x.S12 * (1 + 1e-12)  # transverse shear is matrix-dominated: never above S12 here


@pytest.mark.parametrize("name", NAMES)
def test_failure_strains_are_physical(name):
    """The strengths over the moduli give the failure strains of the constituents: fibre direction 0.5–3 %
    (carbon fibres fail at 0.8–1.8 %, E-glass near 2.5–3 %), transverse tension 0.2–1 % (a cured epoxy
    between fibres fails well below its neat strain), shear strain S12/G12 below 5 %."""
    p = PLIES[name]
    x = p.strength
    assert 0.005 <= x.Xt / p.E1 <= 0.03
    assert 0.002 <= x.Yt / p.E2 <= 0.01
    assert x.S12 / p.G12 <= 0.05


@pytest.mark.parametrize("name", NAMES)
def test_elastic_constants_are_consistent(name):
    """E1/E2 of 3–25 (glass to carbon), E2/G12 of 1.2–2.5, and the compliance built from the ply obeys
    reciprocity ν21 = ν12·E2/E1 and the closed-form positive-definiteness condition of an orthotropic solid,
    1 − ν12ν21 − ν23ν32 − ν13ν31 − 2ν21ν32ν13 > 0 (Jones, Mechanics of Composite Materials, §2.4)."""
    p = PLIES[name]
    assert 3.0 <= p.E1 / p.E2 <= 25.0
    assert 1.2 <= p.E2 / p.G12 <= 2.5
    assert 0.0 < p.nu23 < 1.0 and abs(p.nu12) < np.sqrt(p.E1 / p.E2)
    S = np.linalg.inv(ply_stiffness(p))
    nu21 = -S[0, 1] / S[1, 1]  # lateral contraction along 1 under a stress along 2
    assert nu21 == pytest.approx(p.nu12 * p.E2 / p.E1, rel=1e-9)
    nu21, nu32, nu31 = p.nu12 * p.E2 / p.E1, p.nu23 * p.E3 / p.E2, p.nu13 * p.E3 / p.E1
    assert 1 - p.nu12 * nu21 - p.nu23 * nu32 - p.nu13 * nu31 - 2 * nu21 * nu32 * p.nu13 > 0
    if p.E3 == p.E2 and p.G13 == p.G12:  # transversely isotropic: G23 follows from E2 and ν23
        assert p.G23 == pytest.approx(p.E2 / (2 * (1 + p.nu23)), rel=1e-12)


@pytest.mark.parametrize("name", NAMES)
def test_density_follows_the_rule_of_mixtures(name):
    """The ply density is the volume average of fibre and resin densities at the source's fibre fraction
    (within 4 %, the spread of the constituent densities); without a known V_f the density implies one
    of an autoclaved prepreg (0.5–0.75)."""
    vf, rho_f, rho_m = CONSTITUENTS[name]
    rho = PLIES[name].density
    if vf is None:
        assert 0.5 <= (rho - rho_m) / (rho_f - rho_m) <= 0.75
    else:
        assert rho == pytest.approx(vf * rho_f + (1 - vf) * rho_m, rel=0.04)


def test_im7_8552_ply_carries_its_fibre_areal_weight():
    """The IM7/8552 cured ply holds the 134 g/m² of fibre of the HexPly 8552/35 %/134 prepreg it is made of:
    V_f·ρ_f·t = 0.577 × 1770 kg/m³ × t (the data sheet's fibre fraction and density)."""
    vf, rho_f, _ = CONSTITUENTS["IM7/8552"]
    assert vf * rho_f * PLIES["IM7/8552"].thickness == pytest.approx(0.134, rel=0.01)


@pytest.mark.parametrize("name", NAMES)
def test_catalogue_ply_names_its_sources(name):
    """Each catalogue ply names where its constants and its strengths come from (author and year), and
    says "unverified" for the G_IIc it does not take from a table (all but IM7/8552)."""
    p = PLIES[name]
    assert any(str(year) in p.source for year in range(1950, 2030)) or "docs/" in p.source
    assert any(str(year) in p.strength.source for year in range(1950, 2030))
    if name != "IM7/8552":
        assert "unverified" in p.strength.source
