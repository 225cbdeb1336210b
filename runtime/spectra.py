"""Amplitude spectrum and spectrogram of the tangential velocity X1' (Fig. 2b, 2c).

Amplitudes are normalised so that a sine of amplitude A reads A: the windowed
transform is divided by the sum of the window and doubled (one-sided spectrum).
A peak's amplitude is not read off the FFT grid, where the window's scalloping loss
would bias it, but from the windowed transform evaluated at the peak frequency
itself, found by maximising it in a band.
"""
from __future__ import annotations

import numpy as np
from scipy import optimize, signal

__all__ = ["amplitude_spectrum", "peak_amplitude", "peak_amplitudes", "spectrogram"]


def _window(name, n):
    return signal.get_window(name, n, fftbins=False)


def amplitude_spectrum(x, dt, window="hann", pad=4):
    """One-sided amplitude spectrum of a uniformly sampled signal (mean removed).

    Parameters
    ----------
    x : array_like
        samples, spacing ``dt`` [s]
    window : str
        a `scipy.signal.get_window` name
    pad : int
        zero padding factor (finer frequency grid; does not change amplitudes)

    Returns
    -------
    omega : ndarray [rad/s]
    amplitude : ndarray, same unit as ``x``
    """
    x = np.asarray(x, dtype=float)
    if x.ndim != 1 or x.size < 8:
        raise ValueError("x must be a 1-D signal with at least 8 samples")
    if not dt > 0:
        raise ValueError(f"dt must be > 0; got {dt!r}")
    w = _window(window, x.size)
    n = int(pad) * x.size
    spec = 2 * np.abs(np.fft.rfft((x - x.mean()) * w, n)) / w.sum()
    return 2 * np.pi * np.fft.rfftfreq(n, dt), spec


def _dtft_amplitude(xw, wsum, t, omega):
    phase = omega * t
    return 2 * np.hypot(np.dot(xw, np.cos(phase)), np.dot(xw, np.sin(phase))) / wsum


def peak_amplitudes(x, dt, bands, window="hann"):
    """Largest spectral peak of ``x`` in each band ``(lo, hi)`` [rad/s].

    Each peak is located on a zero-padded FFT and refined by maximising the windowed
    discrete-time Fourier transform; the amplitude is read there, so a pure sine of
    amplitude A at any frequency inside a band reads A (up to the window's leakage
    from other components).

    Returns
    -------
    list of (omega_peak, amplitude), one per band
    """
    x = np.asarray(x, dtype=float)
    omega, spec = amplitude_spectrum(x, dt, window, pad=2)
    w = _window(window, x.size)
    xw, wsum = (x - x.mean()) * w, w.sum()
    t = dt * np.arange(x.size)
    step = omega[1] - omega[0]
    out = []
    for band in bands:
        lo, hi = band
        if not 0 <= lo < hi:
            raise ValueError(f"band must satisfy 0 <= lo < hi; got {band!r}")
        inside = np.flatnonzero((omega >= lo) & (omega <= hi))
        if inside.size == 0:
            raise ValueError(f"band {band!r} holds no frequency of the spectrum (resolution "
                             f"{step:.3g} rad/s, Nyquist {omega[-1]:.3g} rad/s)")
        k = inside[np.argmax(spec[inside])]
        a, b = max(lo, omega[k] - step), min(hi, omega[k] + step)
        # the amplitude is flat at the maximum: a frequency error of 1e-3 of a bin
        # changes it by about 1e-7 relative
        res = optimize.minimize_scalar(lambda om: -_dtft_amplitude(xw, wsum, t, om), bounds=(a, b),
                                       method="bounded", options={"xatol": 1e-3 * step})
        out.append((float(res.x), float(-res.fun)) if -res.fun >= spec[k]
                   else (float(omega[k]), float(spec[k])))
    return out


def peak_amplitude(x, dt, band, window="hann"):
    """`peak_amplitudes` for one band: (omega_peak, amplitude)."""
    return peak_amplitudes(x, dt, [band], window)[0]


def spectrogram(x, dt, segment_s=100.0, overlap=0.5, window="hann"):
    """Spectrogram of ``x`` (Fig. 2c): amplitude against time and frequency.

    Returns
    -------
    t_mid : ndarray [s], centres of the segments (from the first sample)
    omega : ndarray [rad/s]
    amplitude : ndarray, shape (omega.size, t_mid.size), normalised as
        `amplitude_spectrum`
    """
    x = np.asarray(x, dtype=float)
    nper = int(round(segment_s / dt))
    if nper < 8 or nper > x.size:
        raise ValueError(f"segment_s={segment_s!r} must span 8 samples and at most the signal "
                         f"({x.size * dt:.6g} s)")
    if not 0 <= overlap < 1:
        raise ValueError(f"overlap must be in [0, 1); got {overlap!r}")
    f, t, Z = signal.stft(x - x.mean(), fs=1 / dt, window=window, nperseg=nper,
                          noverlap=int(overlap * nper), boundary=None, padded=False,
                          scaling="spectrum")
    return t, 2 * np.pi * f, 2 * np.abs(Z)
