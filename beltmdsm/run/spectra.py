"""Amplitude spectrum and spectrogram of the tangential velocity X1' (Fig. 2b, 2c).

Amplitudes are normalised so that a sine of amplitude A reads A: the windowed
transform is divided by the sum of the window and doubled (one-sided spectrum).
A peak's amplitude is not read off the FFT grid, where the window's scalloping loss
would bias it, but from the windowed transform evaluated at the peak frequency
itself, found by maximising it in a band.
"""

from __future__ import annotations

from collections.abc import Iterable

import numpy as np
from numpy.typing import ArrayLike, NDArray

__all__ = ["amplitude_spectrum", "peak_amplitude", "peak_amplitudes", "spectrogram"]


def _window(name, n):
    # the Hann window of every run's spectrum without importing scipy.signal, which
    # costs half a second of a sweep's start (numpy's is the same symmetric window)
    if name == "hann":
        return np.hanning(n)
    from scipy import signal

    return signal.get_window(name, n, fftbins=False)


def _fast_length(n):
    """The smallest ``2^a 3^b 5^c >= n``: a length numpy's FFT factors into small primes."""
    best = 2 ** int(np.ceil(np.log2(n)))
    power5 = 1
    while power5 < best:
        power35 = power5
        while power35 < best:
            length = power35 * 2 ** max(0, int(np.ceil(np.log2(n / power35))))
            best = min(best, length)
            power35 *= 3
        power5 *= 5
    return best


def amplitude_spectrum(
    x: ArrayLike, dt: float, window: str = "hann", pad: int = 4
) -> tuple[NDArray[np.float64], NDArray[np.float64]]:
    """One-sided amplitude spectrum of a uniformly sampled signal (mean removed).

    Parameters
    ----------
    x : array_like
        samples, spacing ``dt`` [s]
    dt : float
        the sampling step [s]
    window : str
        a `scipy.signal.get_window` name
    pad : int
        zero padding factor (finer frequency grid; does not change amplitudes)

    Returns
    -------
    omega : ndarray [rad/s]
    amplitude : ndarray, same unit as ``x``

    Raises
    ------
    ValueError
        For fewer than 8 samples, a signal that is not 1-D, or ``dt <= 0``.

    See Also
    --------
    peak_amplitudes : a peak's amplitude, refined off the frequency grid.
    spectrogram : the spectrum over time.

    Examples
    --------
    >>> import numpy as np
    >>> dt = 0.01
    >>> t = np.arange(0.0, 100.0, dt)
    >>> x = 2.0 * np.sin(3.0 * t) + 0.5 * np.sin(7.3 * t)
    >>> omega, amplitude = amplitude_spectrum(x, dt)
    >>> k = int(np.argmax(amplitude))
    >>> round(float(omega[k]), 2), round(float(amplitude[k]), 2)
    (3.0, 2.0)
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


_BLOCK = 256


def _dtft_amplitudes(xw, wsum, dt, omegas):
    """``|DTFT|`` of the windowed samples at several frequencies, normalised as the spectrum.

    ``exp(i omega n dt)`` is built as a product of two short tables, ``n = B m + j``
    (``2 sqrt(N)`` complex exponentials instead of ``N`` sines and cosines), each
    factor accurate to an ulp, so the phasor is too.
    """
    n = xw.size
    m = -(-n // _BLOCK)
    j = np.arange(_BLOCK) * dt
    blocks = np.arange(m) * (_BLOCK * dt)
    out = []
    for omega in omegas:
        phasor = np.exp(1j * omega * blocks)[:, None] * np.exp(1j * omega * j)[None, :]
        out.append(2 * abs(np.einsum("i,i->", xw, phasor.ravel()[:n])) / wsum)
    return np.array(out)


def peak_amplitudes(
    x: ArrayLike, dt: float, bands: Iterable[tuple[float, float]], window: str = "hann"
) -> list[tuple[float, float]]:
    """Largest spectral peak of ``x`` in each band ``(lo, hi)`` [rad/s].

    Each peak is located on a zero-padded FFT and refined by maximising the windowed
    discrete-time Fourier transform; the amplitude is read there, so a pure sine of
    amplitude A at any frequency inside a band reads A (up to the window's leakage
    from other components).

    Parameters
    ----------
    x : array_like
        Samples, spacing ``dt`` [s].
    dt : float
        The sampling step [s].
    bands : iterable of (float, float)
        The bands ``(lo, hi)`` [rad/s], ``0 <= lo < hi``.
    window : str
        A `scipy.signal.get_window` name.

    Returns
    -------
    list of (omega_peak, amplitude), one per band

    Raises
    ------
    ValueError
        For fewer than 8 samples, a bad band, or a band that holds no frequency of
        the spectrum (naming its resolution and Nyquist frequency).

    See Also
    --------
    amplitude_spectrum : the whole spectrum on the FFT's grid.

    Examples
    --------
    >>> import numpy as np
    >>> dt = 0.01
    >>> t = np.arange(0.0, 100.0, dt)
    >>> x = 2.0 * np.sin(3.0 * t) + 0.5 * np.sin(7.3 * t)
    >>> [(round(w, 4), round(a, 4)) for w, a in peak_amplitudes(x, dt, [(2, 4), (6, 8)])]
    [(3.0, 2.0), (7.3, 0.5)]
    """
    x = np.asarray(x, dtype=float)
    if x.ndim != 1 or x.size < 8:
        raise ValueError("x must be a 1-D signal with at least 8 samples")
    w = _window(window, x.size)
    xw, wsum = (x - x.mean()) * w, w.sum()
    # the coarse search: at least twofold zero padding, to a length the FFT factors
    # into small primes (the peak is refined off the grid anyway)
    n = _fast_length(2 * x.size)
    spec = 2 * np.abs(np.fft.rfft(xw, n)) / wsum
    omega = 2 * np.pi * np.fft.rfftfreq(n, dt)
    step = omega[1] - omega[0]
    out = []
    for band in bands:
        lo, hi = band
        if not 0 <= lo < hi:
            raise ValueError(f"band must satisfy 0 <= lo < hi; got {band!r}")
        inside = np.flatnonzero((omega >= lo) & (omega <= hi))
        if inside.size == 0:
            raise ValueError(
                f"band {band!r} holds no frequency of the spectrum (resolution "
                f"{step:.3g} rad/s, Nyquist {omega[-1]:.3g} rad/s)"
            )
        k = inside[np.argmax(spec[inside])]
        at, amp = _refine_peak(
            xw, wsum, dt, omega[k], step, max(lo, omega[k] - step), min(hi, omega[k] + step)
        )
        out.append((at, amp) if amp >= spec[k] else (float(omega[k]), float(spec[k])))
    return out


def _refine_peak(xw, wsum, dt, centre, step, lo, hi):
    """The maximum of the windowed transform near a bin, by successive parabolas.

    Three points ``h`` apart around the estimate: where the middle one is the largest,
    the vertex of their parabola becomes the estimate and ``h`` shrinks eightfold;
    otherwise the estimate moves to the largest. It stops at ``h`` = 1e-3 of a bin: the
    amplitude is flat at the maximum, so a frequency error of 1e-3 of a bin changes it
    by about 1e-7 relative.
    """
    h, best = step / 2, centre
    for _ in range(64):
        grid = np.clip(np.array([best - h, best, best + h]), lo, hi)
        a = _dtft_amplitudes(xw, wsum, dt, grid)
        k = int(np.argmax(a))
        if k != 1 and grid[k] != grid[1]:
            best = float(grid[k])
            continue
        curvature = a[0] - 2 * a[1] + a[2]
        if curvature < 0:
            best = float(
                np.clip(
                    grid[1] + h * (a[0] - a[2]) / (2 * curvature), grid[1] - h / 2, grid[1] + h / 2
                )
            )
        if h <= 1e-3 * step:
            break
        h /= 8
    return best, float(_dtft_amplitudes(xw, wsum, dt, [best])[0])


def peak_amplitude(
    x: ArrayLike, dt: float, band: tuple[float, float], window: str = "hann"
) -> tuple[float, float]:
    """`peak_amplitudes` for one band: (omega_peak, amplitude).

    Parameters
    ----------
    x, dt, window
        As for `peak_amplitudes`.
    band : (float, float)
        The band ``(lo, hi)`` [rad/s].

    Returns
    -------
    (float, float)
        The peak's frequency [rad/s] and amplitude.

    Raises
    ------
    ValueError
        As `peak_amplitudes`.

    See Also
    --------
    peak_amplitudes : several bands at once.

    Examples
    --------
    >>> import numpy as np
    >>> t = np.arange(0.0, 100.0, 0.01)
    >>> omega, amplitude = peak_amplitude(0.5 * np.sin(7.3 * t), 0.01, (6.0, 8.0))
    >>> round(omega, 4), round(amplitude, 4)
    (7.3, 0.5)
    """
    return peak_amplitudes(x, dt, [band], window)[0]


def spectrogram(
    x: ArrayLike, dt: float, segment_s: float = 100.0, overlap: float = 0.5, window: str = "hann"
) -> tuple[NDArray[np.float64], NDArray[np.float64], NDArray[np.float64]]:
    """Spectrogram of ``x`` (Fig. 2c): amplitude against time and frequency.

    Parameters
    ----------
    x : array_like
        Samples, spacing ``dt`` [s].
    dt : float
        The sampling step [s].
    segment_s : float
        The length of a segment [s] (at least 8 samples, at most the signal).
    overlap : float
        The overlap of neighbouring segments, a fraction in [0, 1).
    window : str
        A `scipy.signal.get_window` name.

    Returns
    -------
    t_mid : ndarray [s], centres of the segments (from the first sample)
    omega : ndarray [rad/s]
    amplitude : ndarray, shape (omega.size, t_mid.size), normalised as
        `amplitude_spectrum`

    Raises
    ------
    ValueError
        For a segment shorter than 8 samples or longer than the signal, or a bad
        ``overlap``.

    See Also
    --------
    amplitude_spectrum : one spectrum of the whole signal.

    Examples
    --------
    >>> import numpy as np
    >>> dt = 0.01
    >>> t = np.arange(0.0, 100.0, dt)
    >>> x = 2.0 * np.sin(3.0 * t) + 0.5 * np.sin(7.3 * t)
    >>> t_mid, omega, amplitude = spectrogram(x, dt, segment_s=20.0)
    >>> t_mid[:3].tolist(), amplitude.shape
    ([10.0, 20.0, 30.0], (1001, 9))
    """
    x = np.asarray(x, dtype=float)
    nper = int(round(segment_s / dt))
    if nper < 8 or nper > x.size:
        raise ValueError(
            f"segment_s={segment_s!r} must span 8 samples and at most the signal "
            f"({x.size * dt:.6g} s)"
        )
    if not 0 <= overlap < 1:
        raise ValueError(f"overlap must be in [0, 1); got {overlap!r}")
    from scipy import signal

    f, t, Z = signal.stft(
        x - x.mean(),
        fs=1 / dt,
        window=window,
        nperseg=nper,
        noverlap=int(overlap * nper),
        boundary=None,
        padded=False,
        scaling="spectrum",
    )
    return t, 2 * np.pi * f, 2 * np.abs(Z)
