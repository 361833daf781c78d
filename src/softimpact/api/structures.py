"""The structures and the impactor of the notebook API: :class:`Laminate`, :class:`Beam`, :class:`Plate`,
:class:`Bar` and :class:`Sphere`, their quantities parsed to SI once (:func:`softimpact.units.parse`)."""

from __future__ import annotations

from dataclasses import dataclass, field

from ..errors import InputError
from ._edge import _elements, _material, _si, keywords

__all__ = ["Laminate", "Beam", "Plate", "Bar", "Sphere"]


@dataclass(frozen=True, init=False)
class Laminate:
    """A laminate: a ply of the catalogue and a stacking sequence.

    Parameters
    ----------
    ply : str or softimpact.models.laminate.Ply
        A catalogue ply (``"T300/934"``, :data:`softimpact.models.laminate.PLIES`) or a Ply
        (moduli [Pa], density [kg/m³], ply thickness [m]).
    layup : str
        Stacking sequence in degrees from the x axis, ``"[90/0]5s"``, ``"[0/±45/90]s"``.

    Attributes
    ----------
    stack : softimpact.models.laminate.Stack
        The ply and its angles [°]; ``stack.thickness`` [m].

    Raises
    ------
    softimpact.errors.InputError
        An unknown ply or a layup that cannot be read.

    Examples
    --------
    >>> import softimpact as si
    >>> lam = si.Laminate("T300/934", "[90/0]5s")
    >>> len(lam.stack.angles)
    20
    """

    ply: str
    layup: str
    stack: object = field(repr=False, compare=False)

    @keywords("si.Laminate")
    def __init__(self, ply, layup: str):
        from ..models.laminate import PLIES, Ply, Stack, parse_layup

        if isinstance(ply, str):
            if ply not in PLIES:
                raise InputError(f"ply: unknown ply {ply!r} (catalogue: {', '.join(PLIES)})")
            resolved = PLIES[ply]
        elif isinstance(ply, Ply):
            resolved = ply
        else:
            raise InputError(f"ply: expected a catalogue name or a Ply, got {type(ply).__name__}")
        if not isinstance(layup, str):
            raise InputError(f"layup: expected a text such as '[90/0]5s', got {layup!r}")
        object.__setattr__(self, "ply", resolved.name)
        object.__setattr__(self, "layup", layup)
        object.__setattr__(self, "stack", Stack(resolved, parse_layup(layup)))


@dataclass(frozen=True, init=False)
class Beam:
    """A laminated (or isotropic) beam in plane strain, clamped at x = 0 (paper Figs 16–22).

    Parameters
    ----------
    length : str or pint.Quantity
        Free length [length], e.g. ``"6 in"``; x runs from the support (x = 0).
    width : str or pint.Quantity
        Width [length], e.g. ``"1 in"``.
    laminate : Laminate, optional
        The laminate (give this or ``material`` and ``thickness``).
    material : str or Material, optional
        An isotropic catalogue material (``"Al 6061-T6"``) instead of a laminate.
    thickness : str or pint.Quantity, optional
        Thickness [length] of an isotropic beam (a laminate's is its plies').
    elements : (int, int)
        Q4 elements along the length and through the thickness; default (200, 6).
    support : str
        ``"clamped-free"`` (default) or another of :data:`softimpact.fem.plane.SUPPORTS`.
    model : str
        ``"smeared"`` (homogenised laminate, default) or ``"layered"`` (ply group by ply group).
    plane : str
        ``"strain"`` (default) or ``"stress"`` across the width.
    lumped : bool
        Lumped instead of consistent mass matrix.
    kinematics : str
        ``"linear"`` (small deflection, the paper's model; default) or ``"von-karman"`` (large deflection:
        the plane model's total Lagrangian form, :mod:`softimpact.fem.plane_tl`), as ``[beam] kinematics``
        of a case file.

    Attributes
    ----------
    spec : softimpact.workflows.beam_impact.BeamSpec
        The beam in SI.

    Raises
    ------
    softimpact.errors.InputError
        A missing unit, a non-positive size, both or neither of laminate and material.

    Examples
    --------
    >>> import softimpact as si
    >>> beam = si.Beam(length="6 in", width="1 in", laminate=si.Laminate("T300/934", "[90/0]5s"), elements=(200, 6))
    >>> round(beam.spec.length / 0.0254, 12)
    6.0
    """

    spec: object

    @keywords("si.Beam")
    def __init__(
        self,
        *,
        length,
        width,
        laminate: Laminate | None = None,
        material=None,
        thickness=None,
        elements=(200, 6),
        support: str = "clamped-free",
        model: str = "smeared",
        plane: str = "strain",
        lumped: bool = False,
        kinematics: str = "linear",
    ):
        from ..fem.plane import SUPPORTS
        from ..workflows.beam_impact import BeamSpec

        if (laminate is None) == (material is None):
            raise InputError("Beam: give exactly one of laminate and material")
        if support not in SUPPORTS:
            raise InputError(f"support: {support!r} is not one of {', '.join(SUPPORTS)}")
        nx, nz = _elements(elements, 2, "elements")
        mat = _material(material, "material") if material is not None else None
        if mat is not None and thickness is None:
            raise InputError("thickness: an isotropic beam needs its thickness")
        h = _si(thickness, "length", "thickness") if mat is not None else 0.0
        spec = BeamSpec(
            _si(length, "length", "length"),
            _si(width, "length", "width"),
            nx,
            nz,
            support,
            laminate.stack if laminate is not None else None,
            model,
            mat,
            h,
            plane,
            bool(lumped),
            kinematics=kinematics,
        )
        spec.plane_beam()  # checks sizes now, naming the argument
        object.__setattr__(self, "spec", spec)

    @property
    def kinematics(self) -> str:
        """``"linear"`` or ``"von-karman"``, as given."""
        return self.spec.kinematics


@dataclass(frozen=True, init=False)
class Plate:
    """A rectangular laminated plate, first-order shear deformation theory (MITC9 or MITC4 elements).

    Parameters
    ----------
    length : str or pint.Quantity
        Length along x, the 0° fibres [length], e.g. ``"8 in"``.
    width : str or pint.Quantity
        Length along y [length].
    laminate : Laminate
        The laminate (or, for a metal skin, ``material`` and ``thickness`` instead).
    material : str or softimpact.models.metals.Metal, optional
        A metal skin: a catalogue metal by name (``softimpact catalogue``'s metals table, e.g. ``"Al 2024-T3"``) or a
        :class:`~softimpact.models.metals.Metal`, as ``[plate] material`` of a case file.
    thickness : str or pint.Quantity, optional
        The metal skin's thickness [length], e.g. ``"2 mm"``.
    plasticity : bool, optional
        A metal skin elastic–plastic (True, the default for a metal: J2 plasticity through the thickness, its dent
        computed) or elastic (False: checked against yield), as ``[plate] plasticity``.
    elements : (int, int)
        Elements along x and y; default (48, 48).
    support : str or dict
        One support for all four edges, or ``{"x0": ..., "x1": ..., "y0": ..., "y1": ...}``;
        each ``"clamped"``, ``"simply-supported"`` (default), ``"free"`` or ``"symmetry"``.
    element : str
        ``"mitc9"`` (default) or ``"mitc4"``.
    kinematics : str
        ``"linear"`` (small deflection; default) or ``"von-karman"`` (large deflection: membrane
        stretching coupled to bending, :mod:`softimpact.fem.plate_vk`), as ``[plate] kinematics`` of a case file.
    in_plane : str
        Under von Kármán kinematics, the supported edges' restraint in their plane: ``"immovable"``
        (default: a panel fastened to a stiff frame) or ``"movable"`` (the edges draw in).

    Attributes
    ----------
    spec : softimpact.workflows.plate.PlateSpec
        The plate in SI.
    kinematics, in_plane : str
        As given.
    plasticity : bool or None
        As given (None: the default of the plate's material).

    Raises
    ------
    softimpact.errors.InputError
        A missing unit, an unknown support, a plate left a mechanism.

    Examples
    --------
    >>> import softimpact as si
    >>> plate = si.Plate(length="8 in", width="8 in", laminate=si.Laminate("T300/934", "[90/0]5s"), elements=(8, 8))
    >>> plate.spec.supports
    ('simply-supported', 'simply-supported', 'simply-supported', 'simply-supported')
    >>> skin = si.Plate(length="125 mm", width="125 mm", material="Al 2024-T3", thickness="2 mm", elements=(4, 4))
    >>> round(skin.spec.material.yield_stress / 1e6)
    345
    """

    spec: object
    kinematics: str = "linear"
    in_plane: str = "immovable"
    plasticity: bool | None = None

    @keywords("si.Plate")
    def __init__(
        self,
        *,
        length,
        width,
        laminate: Laminate | None = None,
        material=None,
        thickness=None,
        plasticity: bool | None = None,
        elements=(48, 48),
        support="simply-supported",
        element: str = "mitc9",
        kinematics: str = "linear",
        in_plane: str = "immovable",
    ):
        from ..fem.plate_vk import IN_PLANE, KINEMATICS
        from ..input.plate_case import PLATE_SUPPORTS, check_supports
        from ..workflows.plate import PlateSpec

        edges = ("x0", "x1", "y0", "y1")
        if isinstance(support, str):
            supports = (support,) * 4
        elif isinstance(support, dict) and set(support) == set(edges):
            supports = tuple(support[e] for e in edges)
        else:
            raise InputError(f"support: expected one support or a dict of the edges {edges}, got {support!r}")
        for s in supports:
            if s not in PLATE_SUPPORTS:
                raise InputError(f"support: {s!r} is not one of {', '.join(PLATE_SUPPORTS)}")
        check_supports(supports)
        stack, metal_, h = _skin(laminate, material, thickness, plasticity)
        if kinematics not in KINEMATICS:
            raise InputError(f"kinematics: {kinematics!r} is not one of {', '.join(KINEMATICS)}")
        if in_plane not in IN_PLANE:
            raise InputError(f"in_plane: {in_plane!r} is not one of {', '.join(IN_PLANE)}")
        spec = PlateSpec(
            _si(length, "length", "length"),
            _si(width, "length", "width"),
            _elements(elements, 2, "elements"),
            stack,
            supports,
            element=element,
            material=metal_,
            thickness=h,
        )
        object.__setattr__(self, "spec", spec)
        object.__setattr__(self, "kinematics", kinematics)
        object.__setattr__(self, "in_plane", in_plane)
        object.__setattr__(self, "plasticity", plasticity)


def _skin(laminate, material, thickness, plasticity):
    """(stack, metal, thickness [m]) of si.Plate's laminate or metal skin, each refusal naming the user's keyword."""
    from ..models.metals import METALS, Metal, metal

    if material is None:
        if thickness is not None or plasticity is not None:
            which = "thickness" if thickness is not None else "plasticity"
            raise InputError(f"{which}: goes with a metal skin's material (a laminate's thickness is its plies', and it is elastic)")
        if not isinstance(laminate, Laminate):
            raise InputError(f"laminate: expected a si.Laminate (or material and thickness for a metal skin), got {type(laminate).__name__}")
        return laminate.stack, None, None
    if laminate is not None:
        raise InputError("material: a plate is a laminate or a metal skin (material and thickness), not both")
    if isinstance(material, str):
        material = metal(material, "material")
    elif not isinstance(material, Metal):
        raise InputError(f"material: expected a metal's name ({', '.join(METALS)}) or a Metal, got {type(material).__name__}")
    if thickness is None:
        raise InputError('thickness: a metal skin needs its thickness, e.g. thickness="2 mm"')
    if plasticity is not None and not isinstance(plasticity, bool):
        raise InputError(f"plasticity: expected True or False, got {plasticity!r}")
    return None, material, _si(thickness, "length", "thickness")


@dataclass(frozen=True, init=False)
class Bar:
    """A uniform circular bar struck on its end (the paper's instrumented bar, Figs 4–6).

    Parameters
    ----------
    material : str or Material
        A catalogue material, e.g. ``"Al 6061-T6"``.
    length : str or pint.Quantity
        Length [length], e.g. ``"36 in"``.
    diameter : str or pint.Quantity
        Diameter [length], e.g. ``"0.5 in"``.
    elements : int
        Hermite rod elements; default 39.
    end_cap : dict, optional
        A cap on the struck end, ``{"material": ..., "diameter": ..., "length": ...}`` [length].

    Attributes
    ----------
    spec : softimpact.models.specimens.BarSpec
        The bar in SI; gauge positions are measured from the struck end.

    Raises
    ------
    softimpact.errors.InputError
        A missing unit or an unknown material.

    Examples
    --------
    >>> import softimpact as si
    >>> bar = si.Bar("Al 6061-T6", length="36 in", diameter="0.5 in")
    >>> bar.spec.elements
    39
    """

    spec: object

    @keywords("si.Bar")
    def __init__(self, material, *, length, diameter, elements: int = 39, end_cap: dict | None = None):
        from ..models.specimens import BarSpec, EndCap

        cap = None
        if end_cap is not None:
            if not isinstance(end_cap, dict) or set(end_cap) != {"material", "diameter", "length"}:
                raise InputError(f"end_cap: expected {{'material', 'diameter', 'length'}}, got {end_cap!r}")
            cap = EndCap(
                _material(end_cap["material"], "end_cap.material"),
                _si(end_cap["diameter"], "length", "end_cap.diameter"),
                _si(end_cap["length"], "length", "end_cap.length"),
            )
        (n,) = _elements(elements, 1, "elements")
        spec = BarSpec(_material(material, "material"), _si(length, "length", "length"), _si(diameter, "length", "diameter"), n, cap)
        object.__setattr__(self, "spec", spec)


@dataclass(frozen=True, init=False)
class Sphere:
    """A rigid sphere striking the structure.

    Parameters
    ----------
    material : str or Material
        A catalogue material (``"steel"``); its elastic constants enter Hertz's law (eqs 1–3). ``"ice"``
        (hail) and ``"gelatin"`` (the bird substitute) also carry their crushing strength and Hugoniot:
        their laws are ``law="crushing"`` and ``law="hydrodynamic"`` of :func:`softimpact.impact`
        (:meth:`law`).
    diameter : str or pint.Quantity
        Diameter [length], e.g. ``"0.5 in"``.
    velocity : str or pint.Quantity
        Impact velocity toward the target [velocity], e.g. ``"100 in/s"``.
    mass : str or pint.Quantity, optional
        Mass [mass]; default that of a solid sphere of the material.

    Attributes
    ----------
    material : Material
    diameter : float
        [m]
    velocity : float
        [m/s]
    mass : float
        [kg]
    length : float or None
        [m] a bird substitute's overall length (:func:`bird`: a hemispherical-ended cylinder of this ``diameter``,
        striking nose first); None for a sphere
    threat : SubstituteBird or None
        the bird threat it was built from (:func:`bird`), written to summary.json's ``threat``

    Raises
    ------
    softimpact.errors.InputError
        A missing unit, a non-positive size, an unknown material.

    Examples
    --------
    >>> import softimpact as si
    >>> ball = si.Sphere("steel", "0.5 in", velocity="100 in/s")
    >>> round(ball.velocity, 12)
    2.54
    >>> hail = si.Sphere("ice", "38.1 mm", velocity="27.3 m/s")
    >>> type(hail.law("crushing")).__name__
    'CrushingLaw'
    """

    material: object
    diameter: float
    velocity: float
    mass: float
    length: float | None
    threat: object

    @keywords("si.Sphere")
    def __init__(self, material, diameter, *, velocity, mass=None):
        from ..models.materials import sphere_mass
        from ..models.specimens import Impactor

        mat = _material(material, "material")
        d = _si(diameter, "length", "diameter")
        if not d > 0:  # before the mass it gives (the case file's check, naming the argument)
            raise InputError(f"diameter: must be positive, got {diameter!r}")
        v = _si(velocity, "velocity", "velocity")
        m = sphere_mass(mat, d) if mass is None else _si(mass, "mass", "mass")
        if mass is not None:  # the case file's check: a mass its material and size cannot have
            from ..input.projectile import check_mass

            check_mass(mat, d, m, "mass", mass)
        Impactor(m, d, v)  # the same checks as every other path
        for k, value in (("material", mat), ("diameter", d), ("velocity", v), ("mass", m), ("length", None), ("threat", None)):
            object.__setattr__(self, k, value)

    def law(self, name: str):
        """The contact law ``name`` of the sphere's own material (:data:`~softimpact.models.contact_laws.MATERIAL_LAWS`:
        ``"crushing"`` for ice, ``"hydrodynamic"`` for gelatin), for this diameter, mass and velocity.

        Raises InputError (``law``) for another name, (``material``) for a material without the law's data."""
        from ..models.contact_laws import CONTACT_LAWS, MATERIAL_LAWS

        if name not in MATERIAL_LAWS:
            raise InputError(f"law: {name!r} is not a law of the sphere's material (known: {', '.join(MATERIAL_LAWS)})", "law")
        if self.length is not None:  # a bird substitute: the hydrodynamic law of its hemispherical-ended cylinder
            return CONTACT_LAWS[name].of(self.material, self.diameter, self.mass, self.velocity, length=self.length)
        return CONTACT_LAWS[name].of(self.material, self.diameter, self.mass, self.velocity)

    @property
    def impactor(self):
        """The rigid impactor of the coupled stepper (:class:`softimpact.models.specimens.Impactor`)."""
        from ..models.specimens import Impactor

        return Impactor(self.mass, self.diameter, self.velocity)


@keywords("si.bird")
def bird(mass, *, velocity, density=None) -> Sphere:
    """A bird threat as its gelatin substitute: the impactor of a bird of ``mass`` at ``velocity``, as a case file's
    ``threat = { bird = ... }`` builds it (:func:`softimpact.models.threats.substitute_bird`).

    A hemispherical-ended cylinder of gelatin, L/D = 2, of ``density`` (default 950 kg/m³, Wilbeck's), of diameter
    D = (12·m/(5·π·ρ))^(1/3) and length 2·D, striking nose first; its law is ``law="hydrodynamic"``, which acts on
    the cylinder's section for the time L/V the bird takes to flow.

    Parameters
    ----------
    mass : str or pint.Quantity
        The bird's mass [mass], e.g. ``"1.8 kg"`` or ``"4 lb"``.
    velocity : str or pint.Quantity
        Impact velocity toward the target [velocity], required: a bird has no speed of its own.
    density : str or pint.Quantity, optional
        The substitute's density [density]; default 950 kg/m³.

    Returns
    -------
    Sphere
        The impactor: ``material`` gelatin, the bird's ``mass`` [kg], the cylinder's ``diameter`` and ``length`` [m],
        ``velocity`` [m/s] and the ``threat`` (:class:`~softimpact.models.threats.SubstituteBird`).

    Raises
    ------
    softimpact.errors.InputError
        A missing unit, a non-positive mass, density or velocity.

    Examples
    --------
    >>> import softimpact as si
    >>> b = si.bird("1.8 kg", velocity="150 m/s")
    >>> round(b.diameter * 1e3, 1), round(b.length * 1e3, 1)
    (113.1, 226.2)
    >>> type(b.law("hydrodynamic")).__name__
    'HydrodynamicCapsuleLaw'
    """
    from ..models.materials import CATALOGUE
    from ..models.specimens import Impactor
    from ..models.threats import BIRD_SUBSTITUTE_DENSITY, substitute_bird

    m = _si(mass, "mass", "mass")
    rho = BIRD_SUBSTITUTE_DENSITY if density is None else _si(density, "density", "density")
    v = _si(velocity, "velocity", "velocity")
    threat = substitute_bird(m, rho)
    Impactor(threat.mass, threat.diameter, v)  # the same checks as every other path
    sphere = object.__new__(Sphere)
    for k, value in (
        ("material", CATALOGUE["gelatin"]),
        ("diameter", threat.diameter),
        ("velocity", v),
        ("mass", threat.mass),
        ("length", threat.length),
        ("threat", threat),
    ):
        object.__setattr__(sphere, k, value)
    return sphere
