"""sweep, lyapunov and resonance against closed forms and other methods."""

import numpy as np

import impactkit


def test_resonance_is_the_closed_form_linear_response():
    s = impactkit.System.paper()
    r = impactkit.resonance(s, from_=0.2, to=2.4, steps=23)
    np.testing.assert_allclose(r["omega"], np.linspace(0.2, 2.4, 23), rtol=1e-15)
    for omega, rng in zip(r["omega"], r["range"]):
        x = np.linalg.solve(s.stiffness - omega**2 * s.mass + 1j * omega * s.damping, s.forcing)
        np.testing.assert_allclose(rng, 2 * np.abs(x), rtol=1e-12)
    # Peaks near the undamped natural frequencies 0.618 and 1.618 (the eigenvalues of E for N = 2: 2 sin(π/10) and 2 sin(3π/10)).
    assert abs(r["peaks"][0]["omega"] - 0.618) < 0.01


def test_lyapunov_of_a_periodic_orbit_is_log_multipliers_per_period(stable_orbit):
    system, orbit = stable_orbit
    result = impactkit.lyapunov(system, orbit.eta, impacts=2000, transient_impacts=0)
    expected = np.sort(np.log(np.abs(orbit.multipliers)) / system.forcing_period)[::-1]
    assert result["exponents"].shape == (4,)
    np.testing.assert_allclose(result["exponents"], expected, rtol=0, atol=1e-3)


def test_a_sticking_motion_has_p_0_as_every_output_gives_it():
    # check_kind_schema.sh checks the command line's files at the same value.
    run = impactkit.sweep(impactkit.System.paper(), from_=0.2, to=0.2, steps=1,
                          transient_periods=300, recorded_periods=20)
    assert (run["kind"][0], run["p"][0], run["q"][0]) == ("sticking", 0, 1)


def test_a_sweep_with_its_defaults_equals_the_command_line(tmp_path):
    # No run flag on either side: both take the library's defaults
    # (SweepOptions), and give the same motions and impacts value for value.
    import csv
    import os
    import subprocess

    summary, out = tmp_path / "s.csv", tmp_path / "o.csv"
    subprocess.run([os.environ["IMPACTKIT_CLI"], "sweep", "--from", "0.6", "--to", "0.64",
                    "--steps", "5", "--summary", str(summary), "--out", str(out)], check=True,
                   capture_output=True)
    run = impactkit.sweep(impactkit.System.paper(), from_=0.6, to=0.64, steps=5)

    def rows(path):
        with open(path) as f:
            return list(csv.DictReader(line for line in f if not line.startswith("#")))

    cells = rows(summary)
    assert [float(c["omega"]) for c in cells] == list(run["values"])
    assert [c["kind"] for c in cells] == run["kind"]
    assert [int(c["p"]) for c in cells] == list(run["p"])
    assert [int(c["q"]) for c in cells] == list(run["q"])
    impacts = rows(out)
    assert [float(i["t"]) for i in impacts] == list(run["impact_t"])
    assert [float(i["phase"]) for i in impacts] == list(run["impact_phase"])
    assert [float(i["velocity"]) for i in impacts] == list(run["impact_velocity"])


def test_sweep_classifies_the_known_orbits_and_ignores_threads():
    s = impactkit.System.paper()
    kwargs = dict(from_=0.6, to=0.64, steps=5, transient_periods=300, recorded_periods=130,
                  chunk_values=2)
    one = impactkit.sweep(s, threads=1, **kwargs)
    two = impactkit.sweep(s, threads=2, **kwargs)
    np.testing.assert_array_equal(one["values"], [0.6, 0.61, 0.62, 0.63, 0.64])
    assert one["termination"] == two["termination"] == "completed"
    # omega = 0.6 is the P(2,1) orbit that find_orbit finds from simulation.
    orbit = impactkit.find_orbit(impactkit.System.paper(0.6))
    assert (one["kind"][0], one["p"][0], one["q"][0]) == ("periodic", orbit.p, orbit.q)
    for key in ("values", "range_contact", "impact_velocity", "impact_offsets", "p", "q"):
        np.testing.assert_array_equal(one[key], two[key])
    assert one["impact_offsets"].shape == (6,) and one["range_offsets"].shape == (6,)
    assert one["impact_offsets"][-1] == one["impact_velocity"].size
    # P(2,1): two impacts and one max - min per recorded period.
    assert one["impact_offsets"][1] == 2 * one["range_offsets"][1]
    assert one["range_offsets"][-1] == one["range_contact"].size == one["range_first"].size
