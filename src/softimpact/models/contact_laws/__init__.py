"""Contact laws for coupled impact: force, tangent, contact radius, stored energy.

A contact law maps the approach α [m] (positive when the bodies overlap) and its
rate α̇ [m/s] to a compressive force F [N] ≥ 0 (no tension, ever). Every law has

- ``force(alpha, rate)``      F [N]
- ``stiffness(alpha, rate)``  ∂F/∂α [N/m]   (Newton's tangent)
- ``damping(alpha, rate)``    ∂F/∂α̇ [N·s/m] (zero for rate-independent laws; the
  coupled solver needs it because α̇ at the new step is affine in α)
- ``radius(alpha)``           contact radius a [m] (the loaded patch follows it)
- ``energy(alpha)``           the recoverable (elastic) energy stored at α [J]

(:class:`ContactLaw`). Scalars in, scalars out; α ≤ 0 gives zero force.

A law with memory (:class:`HistoryLaw`, e.g. Yang–Sun unloading) keeps its
history in an explicit frozen state: ``initial_state()``; ``branch(state)``
returns a memoryless :class:`ContactLaw` valid within one time step;
``advance(state, alpha, rate)`` returns the state after a converged step. Nothing
is mutated. Memoryless laws are their own branch (:func:`branch_of`). A law whose
memory evolves in time (the Maxwell arm) has ``for_time_step(dt)``, which the
solver calls once before stepping.

Laws
----
:class:`HertzLaw`
    F = K·α^n, n = 3/2 (Hertz 1882; paper eqs 1–3), a = sqrt(R·α). On a laminate,
    Sun's form (Sun 1977, NASA CR-1977; Tan & Sun 1985, J. Appl. Mech. 52:6–12)
    uses the laminate's transverse modulus: K = (4/3)·sqrt(R)·E*,
    1/E* = (1 − ν_s²)/E_s + 1/E_2.
:class:`YangSunLaw`
    Hertz loading with permanent indentation on unloading (Yang & Sun 1982, ASTM
    STP 787:425–449; Tan & Sun 1985): unloading F = F_m·((α − α_p)/(α_m − α_p))^q,
    q = 5/2, with α_p = 0 for α_m < α_cr and α_p = α_m·(1 − (α_cr/α_m)^(2/5))
    otherwise. Reloading follows the unloading curve back up to (α_m, F_m) (the
    elastic reload of the same form; Tan & Sun's exponent-1.5 reload is not used).
:class:`HuntCrossleyLaw`
    F = K·α^n·(1 + D·α̇), clipped at zero: Hunt & Crossley 1975 (J. Appl. Mech.
    42:440–445), D = 3(1 − e)/(2·v⁻), or Lankarani & Nikravesh 1990 (J. Mech.
    Des. 112:369–376), D = 3(1 − e²)/(4·v⁻), with e the coefficient of
    restitution and v⁻ the impact velocity.
:class:`SoftProjectileLaw`
    F = (m·V²/d)·k·(α/d)^p·(1 + c·α̇/V), clipped at zero, a = sqrt(d·α)
    (flattening of a sphere, a² = 2Rα − α² ≈ d·α). Why this family: Table I's
    scaling laws F0 = α1·mV²/(2d) and T = α2·d/V say the pulse, written in
    α/d and t·V/d, is the same at every V; of m·α̈ = −F that is true exactly when
    F·d/(mV²) is a function of α/d and α̇/V only. Physically the ball is in
    the hydrodynamic regime: pressure ∝ ρV² (Wilbeck 1978, AFML-TR-77-134) over a
    flattened area ∝ d·α, which is p = 1; the rate term makes the pulse rise fast
    and fall slowly (tF0/T ≈ 0.25) and dissipates energy (rebound e < 1), the
    role of the Hunt–Crossley term. k and c may scale with the diameter,
    k = k_ref·(d/d_ref)^{q_k}, c = c_ref·(d/d_ref)^{q_c} (and, optionally, the
    exponent p_ref·(d/d_ref)^{q_p}); q = 0 is pure geometric similarity. Its parameters are identified from bar tests
    (:mod:`softimpact.workflows.identification`).
:class:`~softimpact.models.crushing_law.CrushingLaw` (``"crushing"``)
    Ice (hail) crushing against the target: F = A(s)·[σ_c(ε̇) + ρ·ṡ²] over the crushed section, no rebound
    (:mod:`softimpact.models.crushing_law`); built by ``CrushingLaw.of(material, diameter, mass, velocity)``.
:class:`~softimpact.models.hydrodynamic_law.HydrodynamicLaw` (``"hydrodynamic"``)
    Gelatin (the bird substitute) flowing against the target: Wilbeck's shock, release and steady flow
    (:mod:`softimpact.models.hydrodynamic_law`); built by ``HydrodynamicLaw.of(...)``.
:class:`ViscoelasticSoftLaw`
    The soft-projectile law in parallel with a Maxwell arm (spring in series with a
    dashpot; with the equilibrium branch, the standard linear solid of Zener 1948,
    *Elasticity and Anelasticity of Metals*; contact of viscoelastic bodies: Lee &
    Radok 1960, J. Appl. Mech. 27:438–444; Ting 1966, J. Appl. Mech. 33:845–854):

        F = (m·V²/d)·[k·(α/d)^p·(1 + c·α̇/V) + σ] ≥ 0 for α > 0,
        dσ/dt = κ·d(α⁺/d)/dt − σ·V/(θ·d),   α⁺ = max(α, 0).

    Why: a memoryless F(α, α̇) unloads along one curve, so the rate term that makes the
    pulse rise fast also cuts the force off as soon as the ball rebounds, and the
    measured pulses fall fast to a low force that lingers while the ball is still in
    contact (the tail, Fig 7). The arm is stiff on the fast loading, relaxes near the
    peak and pulls the force down on the fast unloading; once it has relaxed, the
    equilibrium branch carries the lingering force. The arm's stress, like the rest,
    is in units of m·V²/d and its relaxation time θ·d/V in units of the transit time:
    only then is F·d/(mV²) a function of α/d, α̇/V and t·V/d, as Table I's scaling
    laws (one pulse shape at every velocity) require. A fixed material relaxation time
    would change the tail's share by the series' 5:1 velocity range; in the
    hydrodynamic regime the flowing material's response time is the transit time
    (Wilbeck 1978). κ, θ may scale with the diameter as k and c do. Out of contact
    (α ≤ 0) the arm's strain α⁺ stays 0 and σ relaxes. Over one time step Δt the arm
    is integrated exactly for a strain rate constant over the step (the branch is
    affine in α⁺), so the law is a :class:`HistoryLaw` bound to the solver's step
    (``for_time_step``). Recoverable energy: the equilibrium branch's plus the arm
    spring's ½·(mV²/d)·d·σ²/κ; the dashpots dissipate.

Modules: :mod:`.hertz`, :mod:`.yang_sun`, :mod:`.hunt_crossley`, :mod:`.soft` (one per law family); the
table :data:`CONTACT_LAWS` of names lives here. A new law costs its class (declaring its optional
capabilities, :mod:`softimpact.models.protocols`), its row below and its validity envelope
(:mod:`softimpact.models.validity`): the approach and contact radius every law is checked on, and a law's
own (:class:`~softimpact.models.protocols.EnvelopedLaw`, ``validity(velocity)``), which :func:`law_validity`
adds to every run that uses the law.
"""

from __future__ import annotations

from collections.abc import Callable

from ...errors import InputError
from ..crushing_law import CrushingLaw
from ..hydrodynamic_law import HydrodynamicLaw
from ..protocols import ContactLaw, EnvelopedLaw, HistoryLaw
from .hertz import HERTZ_DURATION, HertzLaw, effective_modulus, laminate_modulus
from .hunt_crossley import HuntCrossleyLaw
from .soft import MaxwellBranch, MaxwellState, SoftProjectileLaw, ViscoelasticSoftLaw
from .yang_sun import YangSunBranch, YangSunLaw, YangSunState

__all__ = [
    "CONTACT_LAWS",
    "MATERIAL_LAWS",
    "HERTZ_DURATION",
    "HertzLaw",
    "YangSunLaw",
    "YangSunState",
    "YangSunBranch",
    "HuntCrossleyLaw",
    "SoftProjectileLaw",
    "ViscoelasticSoftLaw",
    "MaxwellState",
    "MaxwellBranch",
    "laminate_modulus",
    "effective_modulus",
    "branch_of",
    "resolve_law",
    "law_name",
    "law_validity",
]


def branch_of(law, state) -> ContactLaw:
    """The memoryless law to use in a step: ``law.branch(state)`` or ``law`` itself."""
    return law.branch(state) if isinstance(law, HistoryLaw) else law


# The contact laws by name (case files' ``contact.law``), each with the class it builds: one table,
# as scipy's ``METHODS``. "crushing" (ice) and "hydrodynamic" (gelatin) are built from the projectile's
# material by their ``.of(material, diameter, mass, velocity)``. "identified" is a law.json of ``softimpact identify``: the soft-projectile
# law (or its viscoelastic extension, :class:`ViscoelasticSoftLaw`).
CONTACT_LAWS = {
    "hertz": HertzLaw,
    "hertz-unloading": YangSunLaw,
    "hunt-crossley": HuntCrossleyLaw,
    "identified": SoftProjectileLaw,
    "crushing": CrushingLaw,
    "hydrodynamic": HydrodynamicLaw,
}
# The laws of the projectile's own material (ice, gelatin), built by ``CONTACT_LAWS[name].of(material,
# diameter, mass, velocity)`` from the sphere alone.
MATERIAL_LAWS = ("crushing", "hydrodynamic")


def resolve_law(law, hertz: Callable[[], HertzLaw]):
    """A contact law given as a name of :data:`CONTACT_LAWS` or as an object, resolved in one place.

    ``"hertz"`` is the pair's own Hertz law, ``hertz()``; the other names need their parameters
    (restitution, a law file…), so they come as objects (a :class:`ContactLaw` or a
    :class:`HistoryLaw`), returned as they are. InputError (argument ``law``) otherwise.
    """
    if isinstance(law, str):
        if law not in CONTACT_LAWS:
            raise InputError(f"unknown contact law {law!r} (known: {', '.join(CONTACT_LAWS)})", "law")
        if law != "hertz":
            raise InputError(f"contact law {law!r} needs its parameters: give the law object ({CONTACT_LAWS[law].__name__})", "law")
        return hertz()
    if not isinstance(law, (ContactLaw, HistoryLaw)):
        raise InputError(f"law must be one of {', '.join(CONTACT_LAWS)} or a contact law object, got {type(law).__name__}", "law")
    return law


def law_name(law) -> str:
    """The name of :data:`CONTACT_LAWS` a law object (or name) goes by; the class name if none."""
    if isinstance(law, str):
        return law
    for name, cls in CONTACT_LAWS.items():
        if type(law) is cls:
            return name
    return "identified" if isinstance(law, ViscoelasticSoftLaw) else type(law).__name__


def law_validity(law, velocity: float):
    """The law's own validity envelope at the impact ``velocity`` [m/s] (an
    :class:`~softimpact.models.protocols.EnvelopedLaw`: the crushing law's strain rate, the hydrodynamic law's
    shock release); an empty :class:`~softimpact.models.validity.Validity` for a law without one (the Hertz
    family's envelope is the approach's, :func:`~softimpact.models.validity.contact_validity`)."""
    from ..validity import Validity

    return law.validity(velocity) if isinstance(law, EnvelopedLaw) else Validity({})
