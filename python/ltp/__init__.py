"""ltp: analysis of linear time-periodic systems x' = A(t) x + B(t) u, y = C(t) x + D(t) u.

The functions are the `ltp` command's, with its options as keyword arguments and the same
defaults; results are objects whose fields are numpy arrays.

Systems
    scene(name_or_path, **parameters)   built-in scene, YAML scene file or OpenFAST .lin files
    scenes()                            the built-in scenes and their parameters
    System.from_fourier(T, A, B, C, D)  numpy Fourier coefficients
    System.from_function(T, A, ...)     a Python callable A(t)
    System.from_samples(T, times, A)    piecewise-constant matrices

Analyses (each runs without the GIL)
    floquet(system, ...)   -> FloquetResult   `ltp floquet`: exponents, multipliers, mode shapes
    hill(system, ...)      -> HillResult      `ltp floquet --method hill`: Hill's method
    hill_study(system, ...) -> HillStudy      `ltp hill`: convergence over the truncation N
    hill_matrix(system, harmonics=N) -> ndarray  the truncated Hill matrix ((2N+1)n square)
    periodic_schur(factors) -> PeriodicSchurForm  the periodic Schur form of a product of
                                              factors (FloquetResult.segment_factors): Z, T,
                                              log_multipliers, where the monodromy overflows
    pfrf(system, freq, ...) -> PfrfResult     `ltp pfrf`: partial FRFs H_z over frequency and order
    snapshot(system, freq, ...) -> SnapshotResult  `ltp snapshot`: frozen-system FRF, Fig. 6
    chart(scene, sweep, ...) -> ChartResult   `ltp chart`: Campbell diagrams, stability maps
    campbell(points, by=...) -> CampbellResult  `ltp campbell`: MBC3 modes tracked over operating points
    mbc(files) -> MbcResult                   `ltp mbc --no-floquet`: the MBC3 table of .lin files
    mbc_check(system, result) -> dict | None  `ltp floquet rotor`'s multi-blade-coordinate check
    deflection(system, result) -> dict    `ltp floquet --deflection-csv`: each mode's deflected
                                          structure over a period (tower-rotor)
    simulate(system, freq, ...) -> SimulationResult  `ltp simulate`: time data of a test (a rig's
                                              speed offset, ramp, tacho, input and output noise)
    identify(time, input, output, ...) -> IdentifyResult  `ltp identify` on numpy arrays
    HarmonicTransferFunction(system)      the HTF as an operator at any complex s; .hinf(), .h2(),
                                          .zeros() (transmission zeros of a square system)

Errors: ltp.InputError (also a ValueError) for bad input, ltp.SceneError for scene files,
ltp.ResourceError when a computation would not fit; all derive from ltp.Error.

    >>> import ltp
    >>> r = ltp.floquet(ltp.scene("mathieu", a=1.5, q=2))
    >>> r.exponents, r.verdict, r.error_estimate
"""
from ._ltp import (  # noqa: F401
    CampbellResult,
    ChartResult,
    Error,
    FloquetResult,
    H2Norm,
    HarmonicTransferFunction,
    HillResult,
    HinfNorm,
    HillStudy,
    IdentifyResult,
    InputError,
    MbcResult,
    PeriodicSchurForm,
    PfrfResult,
    ResourceError,
    SceneError,
    SingularMassError,
    SimulationResult,
    SnapshotResult,
    System,
    TransmissionZeros,
    __version__,
    campbell,
    chart,
    deflection,
    floquet,
    hill,
    hill_matrix,
    hill_study,
    identify,
    mbc,
    mbc_check,
    periodic_schur,
    pfrf,
    scene,
    scenes,
    simulate,
    snapshot,
)

__all__ = [
    "CampbellResult", "ChartResult", "Error", "FloquetResult", "H2Norm", "HarmonicTransferFunction",
    "HillResult", "HinfNorm", "HillStudy", "IdentifyResult",
    "InputError", "MbcResult", "PeriodicSchurForm", "PfrfResult",
    "ResourceError", "SceneError", "SimulationResult", "SingularMassError", "SnapshotResult", "System",
    "TransmissionZeros",
    "campbell", "chart", "deflection", "floquet", "hill", "hill_matrix", "hill_study", "identify", "mbc", "mbc_check", "periodic_schur", "pfrf", "scene",
    "scenes", "simulate", "snapshot",
]
