"""rollfit: rolling friction of a hard sphere or cylinder on a viscoelastic
solid (B.N.J. Persson, Eur. Phys. J. E 33 (2010) 327).

Forward: μ(v) from the complex Young's modulus E*(ω). Inverse: E*(ω) as a
Prony series from measured μ(v). Units are SI: Pa, m, N (sphere load) or
N/m (cylinder load), s, rad/s, m/s; temperatures in °C. The numbers are
those of the `rollfit` command line, bit for bit.
"""

from os import PathLike
from typing import Any, Literal, Self, final

import numpy as np
import numpy.typing as npt

__version__: str
__all__ = [
    "__version__",
    "Material",
    "SLS",
    "Prony",
    "HavriliakNegami",
    "Table",
    "Scene",
    "FitResult",
    "DMA",
    "fit",
    "read_dma",
    "compare",
    "read_data",
]

_Floats = npt.ArrayLike
_Path = str | PathLike[str]

class Material:
    """A viscoelastic solid: its complex Young's modulus E*(ω), Pa."""

    def modulus(self, omega: _Floats) -> npt.NDArray[np.complex128]:
        """E*(ω) = E′ + iE″ (Young's, Pa) at each ω (rad/s, ≥ 0)."""
    def tan_delta(self, omega: _Floats) -> npt.NDArray[np.float64]:
        """tan δ = E″/E′ at each ω (rad/s)."""
    @property
    def static_modulus(self) -> float:
        """E(0), Pa."""

@final
class SLS(Material):
    """Standard linear solid (Eq. 12): E0, E1 (Pa), tau (s)."""

    E0: float
    E1: float
    tau: float
    def __new__(cls, E0: float, E1: float, tau: float) -> Self: ...

@final
class Prony(Material):
    """Prony series (Eq. B2): E*(ω) = E1 − Σ H_k/(1 + iωτ_k); E1, H_k (Pa), tau_k (s)."""

    E1: float
    H: list[float]
    tau: list[float]
    def __new__(cls, E1: float, H: _Floats, tau: _Floats) -> Self: ...

@final
class HavriliakNegami(Material):
    """E*(ω) = E1 + (E0 − E1)/(1 + (iωτ)^α)^β; 0 < E0 < E1 (Pa), tau (s), 0 < alpha, beta ≤ 1."""

    E0: float
    E1: float
    tau: float
    alpha: float
    beta: float
    def __new__(cls, E0: float, E1: float, tau: float, alpha: float, beta: float) -> Self: ...

@final
class Table(Material):
    """Tabulated master curve: omega (rad/s), E_storage, E_loss (Young's, Pa)."""

    omega: list[float]
    E_storage: list[float]
    E_loss: list[float]
    def __new__(cls, omega: _Floats, E_storage: _Floats, E_loss: _Floats) -> Self: ...

@final
class Scene:
    """A rolling scene: body, load, substrate, contact-size rule, material."""

    def __new__(
        cls,
        *,
        shape: Literal["sphere", "cylinder"],
        radius: float,
        load: float,
        poisson: float = 0.5,
        thickness: float | None = None,
        contact: Literal["dynamic", "static"] = "dynamic",
        material: Material | None = None,
        tolerance: float | None = None,
    ) -> Self:
        """radius R (m); load (N for a sphere, N/m for a cylinder); Poisson's
        ratio 0 … 0.5; thickness d (m) of a film on a rigid base (None: a
        half-space); tolerance: relative accuracy of μ (default 1e-6)."""
    @staticmethod
    def from_toml(path: _Path) -> Scene:
        """The scene of a scene file, as `rollfit forward` and `rollfit fit` read it."""
    def mu(self, v: _Floats) -> npt.NDArray[np.float64]:
        """μ at each speed v (m/s, positive, increasing); Eq. (11)/(17)."""
    def mu_and_jacobian(
        self, v: _Floats
    ) -> tuple[npt.NDArray[np.float64], npt.NDArray[np.float64]]:
        """μ(v_i) and J[i, j] = ∂μ(v_i)/∂p_j (1/Pa), p = (E1, H_1, …, H_n)."""
    def modulus(self, omega: _Floats) -> npt.NDArray[np.complex128]:
        """The scene's material E*(ω) (Pa) at each ω (rad/s)."""
    @property
    def speeds(self) -> npt.NDArray[np.float64] | None:
        """The [sweep] speeds of a scene file, m/s."""
    @property
    def material(self) -> Material | None: ...
    @property
    def shape(self) -> Literal["sphere", "cylinder"]: ...
    @property
    def radius(self) -> float:
        """m."""
    @property
    def load(self) -> float:
        """N (sphere) or N/m (cylinder)."""
    @property
    def poisson(self) -> float: ...
    @property
    def thickness(self) -> float | None:
        """m; None for a half-space."""
    @property
    def tolerance(self) -> float | None:
        """Relative tolerance of μ (None without a material)."""
    @property
    def notes(self) -> list[str]: ...

@final
class FitResult:
    """The recovered master curve E*(ω) and the fit folder `rollfit fit` writes."""

    def modulus(self, omega: _Floats) -> npt.NDArray[np.complex128]:
        """E*(ω) (Young's, Pa, reference state) at each ω (rad/s)."""
    def tan_delta(self, omega: _Floats) -> npt.NDArray[np.float64]: ...
    def band(self, omega: _Floats) -> dict[str, npt.NDArray[np.float64]]:
        """Values and 1σ ("…_sigma") of E_storage, E_loss (Pa), tan_delta,
        abs_E (Pa) at each ω (rad/s); NaN outside the determined window."""
    @property
    def curve(self) -> dict[str, npt.NDArray[np.float64]]:
        """modulus.csv as columns."""
    @property
    def window(self) -> tuple[float, float]:
        """The determined window (ω_min, ω_max), rad/s."""
    @property
    def probed_window(self) -> tuple[float, float]:
        """The window the speeds probe, rad/s."""
    @property
    def shift(self) -> dict[str, Any] | None:
        """A temperature set's shift, as in fit.json: "model" "wlf",
        "arrhenius" or "free", its constants and log10 a_T per temperature
        with its 1σ (None where the data do not determine it)."""
    @property
    def joint(self) -> dict[str, Any] | None:
        """A joint fit with DMA data (`dma`), as fit.json's `joint`: each
        part's χ² joint and alone, the compatibility test, κ if fitted,
        the DMA points with the joint curve; None without DMA data."""
    @property
    def warnings(self) -> list[str]: ...
    @property
    def converged(self) -> bool: ...
    @property
    def mu_fit(self) -> npt.NDArray[np.float64]:
        """μ of the fit at the data's speeds."""
    def to_dict(self) -> dict[str, Any]:
        """fit.json's content."""
    def save(self, dir: _Path) -> None:
        """Writes dir/fit.json, modulus.csv and mu.csv (the folder replaced as a whole)."""

@final
class DMA:
    """DMA data: omega (rad/s), Young's E_storage, E_loss (Pa), T (°C)."""

    @property
    def omega(self) -> npt.NDArray[np.float64]: ...
    @property
    def E_storage(self) -> npt.NDArray[np.float64]: ...
    @property
    def E_loss(self) -> npt.NDArray[np.float64]: ...
    @property
    def T(self) -> npt.NDArray[np.float64]: ...
    @property
    def format(self) -> Literal["csv", "trios-lims"]: ...
    @property
    def modulus_kind(self) -> Literal["young", "shear"]: ...
    @property
    def warnings(self) -> list[str]: ...
    @property
    def notes(self) -> list[str]: ...

def fit(
    scene: Scene,
    v: _Floats,
    mu: _Floats,
    sigma: _Floats | None = None,
    T: _Floats | None = None,
    *,
    data_file: str | None = None,
    dma: _Path | None = None,
    dma_sigma: float | None = None,
    friction_factor: Literal["one", "free"] | None = None,
    **settings: Any,
) -> FitResult:
    """Fits E*(ω) to μ(v) (m/s); sigma: 1σ of μ; T: °C. Settings as in a
    scene's [fit] table (method, lambda, seed, starts, terms,
    max_evaluations, tolerance, E1_max, shift, T_ref, cross_check, physics,
    terms_per_decade, tau; anchors E0, E_at, contact_radius; shift is
    "auto", the default, "wlf", "arrhenius" or "free"). dma: a DMA file
    (relative to the current folder; else the scene file's [fit] dma)
    fitted jointly, with dma_sigma (relative σ of E′, E″) and
    friction_factor; the result's `joint` then says whether both describe
    one material. Raises ValueError with the CLI's message for a bad
    value, OSError for a DMA file that cannot be read; Ctrl-C
    interrupts."""

def read_data(path: _Path, sheet: str | None = None) -> dict[str, Any]:
    """A measurement file as `rollfit fit` reads it: v (m/s), mu, sigma, T (°C), notes, warnings."""

def read_dma(
    path: _Path,
    poisson: float = 0.5,
    *,
    modulus: Literal["young", "shear"] | None = None,
    dma_wlf: tuple[float, float, float] | None = None,
) -> DMA:
    """Reads a DMA file (CSV or TRIOS LIMS export); shear moduli become Young's with poisson."""

def compare(
    result: FitResult | _Path,
    dma: DMA | _Path,
    *,
    modulus: Literal["young", "shear"] | None = None,
    dma_wlf: tuple[float, float, float] | None = None,
) -> dict[str, Any]:
    """compare.json's content: the fit against DMA data (as `rollfit compare`)."""
