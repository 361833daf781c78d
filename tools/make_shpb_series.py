"""Generate the built-in synthetic two-bar series `ice-shpb-series` (records + series file): five tests of an ice-like
specimen on aluminium split Hopkinson bars, for `softimpact shpb ice-shpb-series`.

The truth (SYNTHETIC: an ice-LIKE material whose strength law is made up, not a measurement of ice): the specimen is
the catalogue ice's elasticity (E = 9.20 GPa, density 916.7 kg/m³) with a rate-dependent flow stress
σ_f = 30 MPa·(ε̇_p/1000 s⁻¹)^0.2 (fem/split_bar.py, eq. F with ε̇_0 = 1e-3 s⁻¹: a power law within 1e-5 over the rates
tested); published high-rate strengths of ice were not retrieved (docs/shpb.md). Specimens 6 mm long, 12.7 mm across,
between Al 6061-T6 bars of 19.05 mm (the catalogue's), the incident 1 m long with its gauge at 0.5 m, the transmitted
0.8 m with its gauge 0.3 m from the specimen. Each test: a raised-cosine pulse rising in 40 us, 100 us flat, its
amplitude set for a target strain rate (300 to 2000 /s, ε̇ = 2c(ε_I − ε_T)/L_s); the FE set-up (fem/split_bar.py,
0.1-us step) gives the two gauges' strains; quarter bridges (gauge factor 2.1, 5 V, gain 100, tension reading positive)
turn them into volts; white noise of 0.5 % of each record's peak; 50 us of pre-trigger; 480 us sampled at 5 MHz.
Run from the repository root: python tools/make_shpb_series.py
"""

import math
from pathlib import Path

import numpy as np

from softimpact.fem.bar import Rod
from softimpact.fem.split_bar import SpecimenLaw, SplitBar
from softimpact.models.bridge import Bridge
from softimpact.models.materials import lookup
from softimpact.workflows.synthetic_bars import add_noise, loading_pulse, split_bar_test, strain_to_volts

OUT = Path("src/softimpact/data/series")
NAME = "ice-shpb-series"
BAR_D, SPEC_D, SPEC_L = 0.01905, 0.0127, 0.006
STRENGTH_1000, EXPONENT = 30e6, 0.2  # the hidden law: 30 MPa at 1000 /s, exponent 0.2
RATES = (300.0, 500.0, 800.0, 1300.0, 2000.0)  # target strain rates [1/s]
NOISE, SEED = 0.005, 20090101


def main():
    al, ice = lookup("Al 6061-T6"), lookup("ice")
    Ab, As = math.pi * BAR_D**2 / 4, math.pi * SPEC_D**2 / 4
    law = SpecimenLaw(STRENGTH_1000 * (1e-3 / 1000.0) ** EXPONENT, EXPONENT, 1e-3)
    setup = SplitBar(
        Rod(1.0, Ab, al.youngs_modulus, al.density, 400),
        Rod(SPEC_L, As, ice.youngs_modulus, ice.density, 12),
        Rod(0.8, Ab, al.youngs_modulus, al.density, 320),
        law,
    )
    bridge = Bridge("quarter", 2.1, 5.0, 100.0, polarity=-1)
    rng = np.random.default_rng(SEED)
    folder = OUT / NAME
    folder.mkdir(parents=True, exist_ok=True)
    names = []
    for rate in RATES:
        sigma = STRENGTH_1000 * (rate / 1000.0) ** EXPONENT
        eps_t = sigma * As / (al.youngs_modulus * Ab)
        eps_i = rate * SPEC_L / (2 * al.wave_speed) + eps_t
        pulse = loading_pulse(eps_i * al.youngs_modulus * Ab, 40e-6, 100e-6)
        t, inc, tr, _ = split_bar_test(
            setup, pulse, incident_gauge=0.5, transmitted_gauge=0.3, time_step=0.1e-6, duration=480e-6, pre_trigger=50e-6, sample_interval=0.2e-6
        )
        vi, vt = strain_to_volts(inc, bridge), strain_to_volts(tr, bridge)
        vi = add_noise(vi, NOISE * float(np.max(np.abs(vi))), rng)
        vt = add_noise(vt, NOISE * float(np.max(np.abs(vt))), rng)
        name = f"ice-{int(rate)}"
        with open(folder / f"{name}.csv", "w") as fh:
            fh.write("time (us),incident (V),transmitted (V)\n")
            for a, b, c in zip(t * 1e6, vi, vt):
                fh.write(f"{a:.2f},{b:.6f},{c:.6f}\n")
        names.append(name)
        print(f"{name}: bar stress {eps_i * al.youngs_modulus / 1e6:.1f} MPa, target strength {sigma / 1e6:.2f} MPa")
    gauge = ['bridge = "quarter"', "gauge_factor = 2.1", 'excitation = "5 V"', "gain = 100"]
    lines = [
        "# Synthetic two-bar series (SYNTHETIC records, not measurements): an ice-LIKE specimen whose rate-dependent strength",
        "# is made up, 30 MPa*(rate/1000 per s)^0.2, tested at 300 to 2000 /s on aluminium bars by the package's FE",
        f"# (tools/make_shpb_series.py, seed {SEED}). `softimpact shpb ice-shpb-series` should recover that law and write it as",
        "# a crushing law.json for hail runs (docs/shpb.md). Published high-rate ice strengths were not retrieved.",
        'title = "Ice-like specimens on aluminium split Hopkinson bars (SYNTHETIC, truth: 30 MPa at 1000 /s, exponent 0.2)"',
        'units = "SI"',
        'synthetic = "records of the two-bar FE (viscoplastic specimen, sigma = 30 MPa (rate/1000 /s)^0.2), quarter bridges, 0.5 % noise"',
        "",
        "[incident_bar]",
        'material = "Al 6061-T6"',
        'length = "1.0 m"',
        'diameter = "19.05 mm"',
        "",
        "[incident_gauge]",
        'position = "0.5 m"',
        *gauge,
        "",
        "[transmitted_bar]",
        'material = "Al 6061-T6"',
        'length = "0.8 m"',
        'diameter = "19.05 mm"',
        "",
        "[transmitted_gauge]",
        'position = "0.3 m"',
        *gauge,
        "",
        "[specimen]",
        'material = "ice"',
        'length = "6 mm"',
        'diameter = "12.7 mm"',
        "",
    ]
    for name in names:
        lines += [
            "[[test]]",
            f'name = "{name}"',
            f'incident = {{ file = "{NAME}/{name}.csv", channel = "incident" }}',
            f'transmitted = {{ file = "{NAME}/{name}.csv", channel = "transmitted" }}',
            "",
        ]
    (OUT / f"{NAME}.toml").write_text("\n".join(lines))


if __name__ == "__main__":
    main()
