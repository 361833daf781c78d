"""The report's display system and the assumptions and errata it lists (from docs/modelling-notes.md)."""

__all__ = ["SYSTEM", "NOTES"]

SYSTEM = "in-lbf-s"  # the paper's units, for the report's own tables and figures

# The assumptions and errata the report lists (from docs/modelling-notes.md).
NOTES = [
    "Bar: Al 6061-T6, E = 10.0e6 psi, ν = 0.33, 0.0975 lb/in³ (handbook). End cap: Al 6061-T6, 1.0 in diameter, "
    "0.25 in long (length assumed), modelled as a mass lumped at the struck end.",
    "Steel ball: 5/8 in, E = 30.0e6 psi, ν = 0.29, 0.283 lb/in³ (handbook); its mass, 16.4 g, follows from the density.",
    "Rubber balls: silicone, 1/2 in → 1.1 g (text); 3/8 in → 0.46 g (same density). Silicone modulus 5 MPa, ν = 0.49 "
    "(representative; used only by the classical Hertz comparison).",
    "Table I: α3 of the 1/2-in ball was lost in the text; 0.25 (the 3/8-in value) is used. The question section's what-if "
    "uses instead the α3 for which Table I's bar law gives Tables II/III's t_F0 (about 0.085), itself a calibration.",
    "The rubber-ball series is SYNTHETIC: the paper's figure data are not available, so records were computed by the "
    "package's bar FE from the Table I model, with a tail, 1 % noise, baseline offsets and arbitrary clocks.",
    "Hertz rigid-wall duration: 2.9433·α_max/V (= 3.2181·(m/K)^(2/5)·V^(-1/5)); the 3.2145 often quoted belongs to the second form.",
    "Eq (4) with Table I gives 36 lbf at 1166 in/s for the 1/2-in ball, where Table II uses 44 lbf: the text and its tables disagree.",
    "T300/934 ply: E1 = 120 GPa, E2 = E3 = 7.9 GPa, G12 = G13 = 5.5 GPa, G23 = 2.82 GPa, ν12 = ν13 = 0.30, ν23 = 0.40, "
    "1580 kg/m³, 0.0055 in per ply (representative literature values; the paper's ref 12 is not available).",
    "Beams: width 1.0 in, 20 plies (0.110 in), free lengths 6.0 in (long) and 4.0 in (short), clamped at x = 0; impact at "
    "mid-length of the free length on the top face; gauge 1 on the bottom face 1.0 in from the impact toward the clamp, "
    "gauge 2 on the bottom face 0.5 in from the clamp; gauge length 0.031 in (all assumed: figure 16 is not in the text).",
    "Eq (14) is written with r0; the cosine distribution is applied over the instantaneous r(t) of eq (10), each node "
    "receiving the exact integral over its tributary segment, so the nodal forces sum to F(t) at every instant.",
    "Tables II and III: the paper's gauge records are not available, so 'measured' strains are SYNTHETIC, computed by a "
    "model 8× as fine as the case (1600 × 48 elements, 0.125 µs, finer than any level calibration uses at its default budget) from the tabulated "
    "histories, with 1.5 % noise and gauge offsets; calibration starts on the paper's 200 × 6 mesh at 1 µs and refines it "
    "within its budget. Table II/III's 'F0, 15' column is read as pounds-force.",
    "Table II's tF0/T is about 0.08, Table I's surviving α3 (3/8 in) is 0.25: the transverse and bar skewness differ "
    "(or the lost 1/2-in α3 was near 0.08). The paper's procedure keeps tF0/T of its start; here it is started with the table's.",
    "Time zero is first contact; compressive force positive; strain tension positive.",
]
