"""Quasi-static delamination onset in the stacked plate against Olsson's threshold F_d = π·sqrt(32·D*·G_IIc/9).

The model: the cohesive plate (:class:`softimpact.fem.cohesive_plate.CohesivePlate`) of an isotropic plate split at
its mid-plane into two sublaminates, with the interface fully damaged over a disc of radius a about the load point
(the faces slide freely; the law's penalty keeps them from interpenetrating) and intact outside. A central point
load P. Linear elastic fracture mechanics gives the energy released per unit area as the disc grows under a fixed
load, G = ½·P²·dC/dA (Irwin–Kies), C the load point's compliance and A the disc's area (here the tributary areas of
the damaged nodes: the compliance is differenced over one element). Growth starts where G = G_IIc (the faces slide:
mode II), so the onset force is F_c = sqrt(2·G_IIc/(dC/dA)). This is the quasi-static limit of a coupled impact (a
large-mass impact's force rises slowly against the plate's first period); Olsson's F_d is that same limit's closed
form (``softimpact.models.delamination``: the formula as given to the project, Olsson's text not retrieved).

Measured (a quarter of a simply supported 200 × 200 mm plate, h = 4 mm, E = 70 GPa, ν = 0.3, MITC9, the
sublaminates' own in-plane fields kept): F_c/F_d = 1.07–1.12 for a/h from 3 to 13 on a 24 × 24 mesh and 1.03–1.11 on
16 × 16, nearly independent of a as Olsson's threshold is (and of the plate: 400 × 400 mm gives 1.10–1.13 for a/h 6 to 29); 0.86–0.90 at a/h ≈ 1, where the disc spans one or two
elements. Davies & Zhang's constant-moment idealisation (the disc's two halves bending freely, D/4 in all) would give
3·P²/(32·π²·D), F_c = √3·F_d: the stacked plate releases 2.4 times that at these sizes, and the exact two-region
Kirchhoff plate (the same idealisation without the constant moment) far more at small a — the halves of an embedded
disc cannot bend freely, their in-plane fields tie them at its edge, which the stacked plate keeps. The experimental
scatter of onset loads around F_d was not retrieved; the tolerance below (15 %) is the measured spread plus the
discretisation's 2 % (16 × 16 against 24 × 24), stated, not a published band.
"""

import math

import numpy as np
import pytest
import scipy.sparse.linalg

from softimpact.fem.cohesive_plate import CohesivePlate
from softimpact.fem.plate import Plate
from softimpact.models.cohesive import BilinearCohesive
from softimpact.models.delamination import olsson_threshold
from softimpact.models.laminate import Ply, Stack
from softimpact.models.plate_laminate import plate_section

E, NU, T_PLY, N_PLY = 70e9, 0.3, 0.5e-3, 8
H = T_PLY * N_PLY
D = E * H**3 / (12 * (1 - NU**2))
GIIC = 800.0  # J/m²: any value (F_c and F_d both scale with its square root)
HALF, N = 0.1, 16  # the quarter's side [m] and elements along it


def onset_ratios(half: float = HALF, n: int = N, discs: int = 8, load=None):
    """(a_eff/h, F_c/F_d) for ``discs`` discs grown element by element from the load point, on a quarter of side
    ``half`` [m] with ``n`` × ``n`` elements (benchmarks/onset_olsson.py runs it on finer and larger plates).

    ``load``: a function of the :class:`CohesivePlate` giving the quarter's nodal load vector (over its stacked DOFs)
    of a unit total force on the whole plate; by default the central point load on the top sublaminate,
    ``cp.deflection(0, 0) / 4`` (tests/test_onset_distributed.py passes a pressure). The compliance is the
    work-conjugate one of that fixed distribution, C = 4·fᵀu/P (the four quarters' work ½·P²·C)."""
    g = E / (2 * (1 + NU))
    ply = Ply("isotropic", E, E, E, g, g, g, NU, NU, NU, 2700.0, T_PLY)
    stack = Stack(ply, (0.0,) * N_PLY)
    law = BilinearCohesive(K=1e15, N=50e6, S=80e6, GIc=300.0, GIIc=GIIC, eta=2.1)
    plate = Plate(half, half, n, n, plate_section(stack), supports=("symmetry", "simply-supported", "symmetry", "simply-supported"), element="mitc9")
    cp = CohesivePlate(plate, stack, (N_PLY // 2,), law, in_plane="movable")
    x, y = cp.layers[0].fe.node_xy()
    r = np.hypot(x, y)
    P = 1.0
    f = (cp.deflection(0.0, 0.0) / 4 if load is None else load(cp)) * P  # the quarter's share of the load
    areas, compliances = [], []
    for a in (np.arange(discs) + 1.25) * half / n:  # radii between node rings, one element apart
        cp.damage[:] = 0.0
        cp.damage[0, r < a] = 1.0
        u = np.zeros(cp.n)
        for _ in range(10):  # the closure penalty acts where the faces would interpenetrate: iterate to its active set
            new = scipy.sparse.linalg.spsolve(cp.tangent(u).tocsc(), f)
            if np.allclose(new, u, rtol=1e-12, atol=0.0):
                break
            u = new
        else:
            raise AssertionError(f"the faces' contact set did not settle at a = {a:.4g} m")
        areas.append(4 * cp.area[r < a].sum())
        compliances.append(4 * (f @ u) / P**2)
    A, C = np.array(areas), np.array(compliances)
    dC_dA = np.diff(C) / np.diff(A)
    F_c = np.sqrt(2 * GIIC / dC_dA)
    a_eff = np.sqrt(0.5 * (A[1:] + A[:-1]) / math.pi)
    return a_eff / H, F_c / olsson_threshold(D, GIIC)


@pytest.fixture(scope="module")
def onset():
    return onset_ratios()


@pytest.mark.slow
def test_quasi_static_onset_force_is_olssons_threshold(onset):
    """For delaminations of 3 to 12 thicknesses the stacked plate's LEFM onset force is Olsson's F_d within 15 % (measured 3-11 % above it)."""
    a_over_h, ratio = onset
    keep = a_over_h >= 2.5
    assert keep.sum() >= 4
    np.testing.assert_allclose(ratio[keep], 1.0, atol=0.15)


@pytest.mark.slow
def test_onset_force_hardly_depends_on_the_delaminations_size(onset):
    """Olsson's threshold does not depend on the delamination's radius; the model's onset force moves by under 10 % from 3 to 12 thicknesses (measured 7 %)."""
    a_over_h, ratio = onset
    keep = a_over_h >= 2.5
    assert ratio[keep].max() / ratio[keep].min() < 1.10
