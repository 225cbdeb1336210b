"""Spectrum normalisation: a sine of amplitude A reads A."""

import numpy as np
import pytest

from beltmdsm.run.spectra import (
    amplitude_spectrum,
    peak_amplitude,
    peak_amplitudes,
    spectrogram,
)

DT = 0.02
T = np.arange(0, 700, DT)


@pytest.mark.parametrize("omega", [1.0, 1.0137, 3.9991])
def test_peak_of_a_sine_reads_its_amplitude_off_the_fft_grid(omega):
    x = 2.5 * np.sin(omega * T + 0.4) + 0.7
    at, amp = peak_amplitude(x, DT, (omega - 0.2, omega + 0.2))
    # the frequency is refined to 1e-3 of a bin: the Hann main lobe then loses < 1e-6
    assert amp == pytest.approx(2.5, rel=1e-6)
    assert at == pytest.approx(omega, abs=2 * np.pi / (T[-1] * 1e2))


def test_two_lines_are_read_separately():
    x = 3.0 * np.sin(1.0 * T) + 0.5 * np.sin(4.0 * T + 1.0)
    (w1, a1), (w2, a2) = peak_amplitudes(x, DT, [(0.75, 1.25), (3.9, 4.1)])
    assert (a1, a2) == (pytest.approx(3.0, rel=1e-6), pytest.approx(0.5, rel=1e-6))


def test_amplitude_spectrum_on_a_bin_reads_the_amplitude():
    n = 4096
    k = 100
    omega = 2 * np.pi * k / (n * DT)
    x = 1.7 * np.cos(omega * DT * np.arange(n))
    om, spec = amplitude_spectrum(x, DT, window="boxcar", pad=1)
    assert om[np.argmax(spec)] == pytest.approx(omega)
    assert spec.max() == pytest.approx(1.7, rel=1e-12)


def test_spectrogram_tracks_a_line_that_switches_on():
    x = np.where(T > 350, 2.0 * np.sin(2 * np.pi * 0.5 * T), 0.0)
    t_mid, om, amp = spectrogram(x, DT, segment_s=50.0)
    row = np.argmin(np.abs(om - 2 * np.pi * 0.5))
    assert amp[row, t_mid < 300].max() < 1e-12
    # 0.5 Hz sits on the 50 s segment's grid: Hann, no scalloping, reads 2.0
    assert amp[row, t_mid > 400].max() == pytest.approx(2.0, rel=1e-9)


def test_bad_inputs_are_named():
    with pytest.raises(ValueError, match="band"):
        peak_amplitude(np.sin(T), DT, (2.0, 1.0))
    with pytest.raises(ValueError, match="dt"):
        amplitude_spectrum(np.sin(T), 0.0)
    with pytest.raises(ValueError, match="segment_s"):
        spectrogram(np.sin(T), DT, segment_s=1e5)


def test_the_fft_length_is_scipys_next_fast_length():
    from scipy.fft import next_fast_len

    from beltmdsm.run.spectra import _fast_length

    for n in [*range(1, 2000), 2**20 + 1, 3**9 + 7, 5**8 - 1, 12_345_679]:
        assert _fast_length(n) == next_fast_len(n, real=True), n
