import math

import numpy as np
import pytest

from isorock.analytic import GroundMotion, InputError, load_motion, read_at2, read_jma, read_two_column

G = 9.81


def test_kobe_at2_loads(kobe_at2):
    m = read_at2(kobe_at2)
    assert m.n == 7500
    assert m.dt == pytest.approx(0.02)
    assert m.pga_g == pytest.approx(0.834, abs=5e-4)
    # peak at 8.52 s (records README)
    assert m.times[np.argmax(np.abs(m.acceleration))] == pytest.approx(8.52, abs=1e-9)


def test_kobe_jma_agrees_with_at2(kobe_jma, kobe_at2):
    j, a = read_jma(kobe_jma), read_at2(kobe_at2)
    assert j.n == 2567 and j.dt == pytest.approx(0.02)
    assert j.pga_g == pytest.approx(0.834, abs=5e-4)
    # an independent check of both readers' units: aligned, they agree sample for sample
    shift = int(round((8.52 - 4.82) / 0.02))
    x, y = j.acceleration, a.acceleration[shift:shift + j.n]
    assert np.corrcoef(x, y)[0, 1] > 0.9999
    assert np.max(np.abs(x - y)) < 0.02 * a.pga


def test_load_motion_guesses_formats(kobe_jma, kobe_at2):
    assert load_motion(str(kobe_at2)).n == 7500
    assert load_motion(str(kobe_jma)).n == 2567


def _write(tmp_path, name, text):
    p = tmp_path / name
    p.write_text(text)
    return p


AT2_HEAD = "PEER NGA\nrecord\nACCELERATION TIME SERIES IN UNITS OF G\nNPTS=    {n}, DT=   .0100 SEC\n"


def test_at2_reads_values_in_g(tmp_path):
    p = _write(tmp_path, "x.AT2", AT2_HEAD.format(n=6) + " .1 .2 -.3 .4 .5\n .0\n")
    m = read_at2(p)
    assert m.dt == 0.01 and m.n == 6
    np.testing.assert_allclose(m.acceleration, np.array([.1, .2, -.3, .4, .5, 0]) * G)


@pytest.mark.parametrize("name,text,match", [
    ("npts.AT2", AT2_HEAD.format(n=7) + " .1 .2 .3\n", "NPTS = 7 but the file has 3"),
    ("word.AT2", AT2_HEAD.format(n=3) + " .1 abc .3\n", "'abc' is not a number"),
    ("nan.AT2", AT2_HEAD.format(n=3) + " .1 nan .3\n", "not a finite number"),
    ("inf.AT2", AT2_HEAD.format(n=3) + " .1 inf .3\n", "not a finite number"),
    ("head.AT2", "a\nb\nc\nno header here\n 1 2\n", "expected 'NPTS = n, DT = dt SEC'"),
    ("empty.AT2", AT2_HEAD.format(n=0), "empty"),
    ("short.AT2", "a\nb\n", "4 header lines"),
])
def test_at2_malformed(tmp_path, name, text, match):
    with pytest.raises(InputError, match=match):
        read_at2(_write(tmp_path, name, text))


def test_jma_reads_gal(tmp_path):
    p = _write(tmp_path, "j", ";c1\n;c2\n0.01 0.5\n 100. -200. 50.\n 0.0\n")
    m = read_jma(p)
    assert m.dt == 0.01
    np.testing.assert_allclose(m.acceleration, [1.0, -2.0, 0.5, 0.0])


@pytest.mark.parametrize("text,match", [
    (";c\n", "no data"),
    (";c\n0.01 0.5\n1 x 3\n", "'x' is not a number"),
    (";c\n0.01 0.5\n", "empty"),
])
def test_jma_malformed(tmp_path, text, match):
    with pytest.raises(InputError, match=match):
        read_jma(_write(tmp_path, "j", text))


def test_two_column_units(tmp_path):
    p = _write(tmp_path, "a.csv", "t,a\n0,0\n0.5,1\n1.0,-1\n")
    assert read_two_column(p, units="g").acceleration[1] == pytest.approx(G)
    assert read_two_column(p, units="gal").acceleration[1] == pytest.approx(0.01)
    m = read_two_column(p, units="m/s2")
    assert m.dt == 0.5 and m(0.25) == pytest.approx(0.5)


@pytest.mark.parametrize("text,match", [
    ("0,0\n0.5,1\n0.7,2\n", "uniformly spaced"),
    ("0,0\n0.5,1\n0.4,2\n", "time must increase"),
    ("0,0\n0.5,1\n0.5,2\n", "time must increase"),
    ("0,0\n0.5\n", "two columns"),
    ("0,0\n0.5,zz\n", "'zz' is not a number"),
    ("0,0\n0.5,nan\n", "not a finite"),
    ("# nothing\n", "no data rows"),
    ("1,0\n2,1\n", "start at 0"),
])
def test_two_column_malformed(tmp_path, text, match):
    with pytest.raises(InputError, match=match):
        read_two_column(_write(tmp_path, "bad.csv", text), units="m/s2")


def test_from_array_checks():
    with pytest.raises(InputError, match="finite"):
        GroundMotion.from_array([0, np.nan, 1], dt=0.01)
    with pytest.raises(InputError, match="empty"):
        GroundMotion.from_array([], dt=0.01)
    with pytest.raises(InputError, match="dt"):
        GroundMotion.from_array([0, 1], dt=-0.01)
    with pytest.raises(InputError, match="units"):
        GroundMotion.from_array([0, 1], dt=0.01, units="furlongs")
    with pytest.raises(InputError, match="exactly one of dt or t"):
        GroundMotion.from_array([0, 1])


def test_linear_between_samples_and_zero_after():
    m = GroundMotion.from_array([0.0, 2.0, -2.0], dt=0.1)
    assert m(0.05) == pytest.approx(1.0)
    assert m.at(0.15) == pytest.approx(0.0)
    assert m(0.2) == pytest.approx(-2.0) and m(0.2001) == 0.0 and m(-0.1) == 0.0
    assert m.end_time == pytest.approx(0.2)


def test_pulses_follow_model_md():
    s = load_motion("sine:amp=0.4,freq=1.5,cycles=2")
    t = np.linspace(0, 2 / 1.5, 101)
    np.testing.assert_allclose(s(t), 0.4 * G * np.sin(2 * math.pi * 1.5 * t), atol=1e-12)
    assert s(2 / 1.5 + 1e-6) == 0.0 and s.end_time == pytest.approx(2 / 1.5)
    c = load_motion("cosine:amp=0.2,freq=2")  # cycles defaults to 1
    assert c(0.0) == pytest.approx(0.2 * G) and c(0.5 + 1e-9) == 0.0
    r = load_motion("ricker:amp=0.5,freq=2")
    tau = 0.3 - 0.5
    x = (math.pi * 2 * tau) ** 2
    assert r(0.3) == pytest.approx(0.5 * G * (1 - 2 * x) * math.exp(-x))
    assert r(0.5) == pytest.approx(0.5 * G)  # peak at τ = 0


@pytest.mark.parametrize("spec,match", [
    ("sine:amp=0.4", "needs freq"),
    ("sine:amp=0.4,freq=-1", "freq"),
    ("sine:amp=x,freq=1", "amp"),
    ("ricker:amp=1,freq=1,cycles=2", "unknown"),
    ("square:amp=1,freq=1", "not a file"),
    ("no/such/file.AT2", "not a file"),
])
def test_bad_motion_specs(spec, match):
    with pytest.raises(InputError, match=match):
        load_motion(spec)


def test_scaling_and_trimming():
    m = GroundMotion.from_array(np.arange(11.0), dt=0.1)
    assert m.scaled(2).pga == pytest.approx(20.0)
    assert m.scaled_to_pga(1.0).pga_g == pytest.approx(1.0)
    t = m.trimmed(0.3, 0.6)
    np.testing.assert_allclose(t.acceleration, [3, 4, 5, 6])
    p = load_motion("sine:amp=1,freq=1").trimmed(0.25)
    assert p(0.0) == pytest.approx(G) and p.end_time == pytest.approx(0.75)
    assert load_motion("sine:amp=1,freq=1").scaled(0.5)(0.25) == pytest.approx(0.5 * G)
    with pytest.raises(InputError, match="end"):
        m.trimmed(0.6, 0.3)


# --- issue 13: read honestly or refuse --------------------------------------------------

@pytest.mark.parametrize("dt", [".", "1.2.3", "-0.01", "0", "nan", "x"])
def test_at2_bad_dt_is_an_input_error(tmp_path, dt):
    text = "PEER\nrec\nACCELERATION TIME SERIES IN UNITS OF G\n" + f"NPTS=    3, DT= {dt} SEC\n .1 .2 .3\n"
    with pytest.raises(InputError, match="DT"):
        read_at2(_write(tmp_path, "x.AT2", text))


@pytest.mark.parametrize("stated,factor", [
    ("UNITS OF G", G), ("IN UNITS OF CM/SEC/SEC", 0.01), ("UNITS OF CM/S/S", 0.01), ("UNITS OF CM/S2", 0.01),
    ("UNITS OF CM/SEC^2", 0.01), ("UNITS OF GAL", 0.01), ("UNITS OF M/S/S", 1.0), ("UNITS: m/s2", 1.0),
    ("units of g", G),
])
def test_at2_reads_the_units_its_header_states(tmp_path, stated, factor):
    text = f"PEER\nrec\nACCELERATION TIME SERIES {stated}\nNPTS=    3, DT= .01 SEC\n 1 2 3\n"
    m = read_at2(_write(tmp_path, "x.AT2", text))
    np.testing.assert_allclose(m.acceleration, np.array([1, 2, 3]) * factor, rtol=1e-3 if factor == G else 1e-15)


@pytest.mark.parametrize("line3,match", [
    ("VELOCITY TIME SERIES IN UNITS OF CM/S", "velocity series"),
    ("DISPLACEMENT TIME SERIES IN UNITS OF CM", "displacement series"),
    ("ACCELERATION TIME SERIES IN UNITS OF CM/S", "not an acceleration"),
    ("ACCELERATION TIME SERIES IN UNITS OF FURLONGS", "not an acceleration"),
    ("ACCELERATION TIME SERIES", "units are not stated"),
])
def test_at2_refuses_what_is_not_an_acceleration_in_known_units(tmp_path, line3, match):
    text = f"PEER\nrec\n{line3}\nNPTS=    3, DT= .01 SEC\n 1 2 3\n"
    with pytest.raises(InputError, match=match):
        read_at2(_write(tmp_path, "x.AT2", text))


def test_units_given_must_agree_with_the_file(tmp_path):
    at2 = _write(tmp_path, "x.AT2", AT2_HEAD.format(n=3) + " .1 .2 .3\n")
    assert load_motion(str(at2), units="g").pga_g == pytest.approx(0.3, rel=1e-3)
    with pytest.raises(InputError, match="contradicts"):
        load_motion(str(at2), units="m/s2")
    bare = _write(tmp_path, "y.AT2", "PEER\nrec\nACCELERATION TIME SERIES\nNPTS=    3, DT= .01 SEC\n 1 2 3\n")
    assert load_motion(str(bare), units="cm/s2").pga == pytest.approx(0.03)
    jma = _write(tmp_path, "j", ";c\n0.01 0.5\n 100. -200.\n")
    assert load_motion(str(jma), units="gal").pga == pytest.approx(2.0)
    with pytest.raises(InputError, match="contradicts"):
        load_motion(str(jma), units="g")


def test_two_column_units_must_be_known(tmp_path):
    p = _write(tmp_path, "a.csv", "0,0\n0.5,0.3\n1.0,-0.3\n")
    with pytest.raises(InputError, match="units are not stated"):
        load_motion(str(p))
    for text, factor in (("# units: g\n0,0\n0.5,0.3\n1.0,-0.3\n", G),
                         ("t [s], a [cm/s2]\n0,0\n0.5,0.3\n1.0,-0.3\n", 0.01),
                         ("time (s),acc (g)\n0,0\n0.5,0.3\n1.0,-0.3\n", G)):
        m = load_motion(str(_write(tmp_path, "b.csv", text)))
        assert m.pga == pytest.approx(0.3 * factor, rel=1e-3)
    with pytest.raises(InputError, match="contradicts"):
        load_motion(str(_write(tmp_path, "c.csv", "# units: g\n0,0\n0.5,0.3\n")), units="m/s2")


def test_byte_order_mark_keeps_the_first_row(tmp_path):
    p = tmp_path / "bom.csv"
    p.write_bytes("\ufeff0,0.5\n0.5,1\n1.0,-1\n".encode("utf-8"))
    m = read_two_column(p, units="m/s2")
    assert m.n == 3 and m.acceleration[0] == 0.5


@pytest.mark.parametrize("spec,match", [
    ("sine:amp=0.1,amp=5,freq=1", "amp is given twice"),
    ("ricker:amp=1,freq=2,freq=3", "freq is given twice"),
    ("sine:amp=0.5,freq=1e-6", "MAX_DURATION"),
    ("cosine:amp=0.5,freq=1,cycles=1e9", "MAX_DURATION"),
    ("sine:amp=0.5,freq=1e6,cycles=1e5", "MAX_SAMPLES"),
])
def test_pulse_specs_are_read_honestly_and_bounded(spec, match):
    with pytest.raises(InputError, match=match):
        load_motion(spec)


def test_record_size_is_bounded():
    from isorock.analytic.limits import MAX_DURATION, MAX_RECORD_SAMPLES
    with pytest.raises(InputError, match="MAX_RECORD_SAMPLES"):
        GroundMotion.from_array(np.zeros(MAX_RECORD_SAMPLES + 1), dt=1e-5)
    with pytest.raises(InputError, match="MAX_DURATION"):
        GroundMotion.from_array(np.zeros(3), dt=MAX_DURATION)


def test_a_scaled_pulse_reports_the_peak_it_applies():
    """A pulse scaled by 2 applies twice its amplitude (its samples and its call agree);
    its PGA said 4× (the samples, already scaled, were scaled again)."""
    import numpy as np

    from isorock.analytic.motion import load_motion
    m = load_motion("sine:amp=0.5,freq=1,cycles=1").scaled(2.0)
    t = np.linspace(0.0, 1.0, 20001)
    applied = float(np.max(np.abs(m(t)))) / m.pga * m.pga_g
    assert m.pga_g == pytest.approx(1.0, rel=1e-3) and applied == pytest.approx(m.pga_g, rel=1e-3)
    assert m.scaled_to_pga(0.3).pga_g == pytest.approx(0.3, rel=1e-9)
