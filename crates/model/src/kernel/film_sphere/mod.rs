//! The kernel of a sphere rolling on a film of thickness d bonded to a rigid
//! base, as a function of two variables, and the universal weights that
//! integrate it on the σ grid.
//!
//! # The kernel
//!
//! The film divides the loss compliance by S(qd) (Persson 2010; S in
//! [`crate::film`]). With ω = qv cos φ and u = 1/cos φ the sphere's Eq. (17)
//! reduces, as for the half-space ([`crate::kernel::sphere`]), to one
//! frequency integral with the kernel
//!
//!   K(τ, λ) = x² ∫₁^∞ f(xu)/S(xuδ) du/√(u² − 1),   x = e^τ = ωr/v,
//!   δ = e^λ = d/r,
//!
//! f the Hertz form factor. K depends on the speed only through τ (like the
//! half-space kernel k_half = x² G(x), which it becomes for δ → ∞) and on the
//! film only through δ; the cost of a film is therefore that of a second
//! table variable, whatever d/r0.
//!
//! # The split
//!
//! For x ≳ 1, K carries the oscillation e^{2ix} of f's endpoint at u = 1.
//! With the exact split f = f_n + Re[e^{2iy} c(y)] of the form factor,
//!
//!   K = N + Re[A e^{2ix}],   N = M₆(δx)/(2x⁴) + M₄(δx)/(2x²),
//!
//! where M_k(z) = ∫₀^∞ cosh^{−k}t / S(z cosh t) dt are one-variable moments
//! ([`moments`]) and A (the amplitude, [`integrals::FilmKernel::amplitude`])
//! is smooth in both variables. The kernel that is integrated is
//!
//!   K̃ = (1 − χ) K + χ N + Re[A E],   E = χ (1 − χ_w) e^{2ix},
//!
//! χ(τ) = ½ erfc(−τ/w) a smooth step at x ≈ 1 (w = ¼) and χ_w the window of
//! [`crate::kernel::window`] that drops the oscillation beyond x ≈ 20
//! (exponentially small change, as for the half-space). Below the step K
//! itself is used; above it only smooth functions of τ are interpolated.
//!
//! # Product integration
//!
//! On the σ grid (step h, stencil of [`crate::kernel::weights::STENCIL`]
//! points) μ ≈ C Σ_j Φ_j w_j with
//!
//!   w_j = R_j W_K(τ_j) + (N/N_h)_j W_N(τ_j) + Re[(A/N_h)_j W_osc(τ_j)],
//!
//! W_K = h ∫ B (1 − χ) k_half, W_N = h ∫ B χ N_h, W_osc = h ∫ B E N_h
//! ([`blend`]; B the cardinal function of the local Lagrange interpolant),
//! N_h = 1/(3x²) + 4/(15x⁴) the half-space's N, and R = K/k_half. What the
//! nodes carry — R, N/N_h ∈ [0, 1] and A/N_h — are bounded, smooth ratios;
//! the steep parts (k_half's logarithm at small x, N_h's x⁻⁴, which nearly
//! cancels against A e^{2ix} below x ≈ 1) are integrated exactly in the
//! weights. For δ → ∞ the ratios are 1, 1 and A_h/N_h, and the rule becomes
//! the half-space's (tested: a film 1e8 contact radii thick gives the
//! half-space μ to within the tolerance at every step).
//!
//! # Tables
//!
//! R and A are tabulated in rows of constant λ on a global grid Δλ = 1/32
//! and, along each row, on τ_m = m h/n (Δτ ≈ 0.02), built once per process
//! per Poisson ratio and grid step for the λ a scene needs ([`rows`]); each
//! row comes from piecewise Chebyshev interpolants of quadratures of K and
//! A ([`integrals`]: contour rotation of the oscillating tail, with the
//! complex continuation of 1/S for thin films). Between rows and points:
//! six-point Lagrange interpolation in both variables, measured below 7e-10
//! of the kernel's scale.
//!
//! # The thin-film limit
//!
//! For d ≪ r the film acts like a Winkler foundation, 1/S(ζ) = βζ + γζ³ + …
//! (β = 0 for ν = ½, where S ~ 3/(2ζ³)): μ falls like d for ν < ½ and like
//! d³ ln(r0/d) for ν = ½. The moments carry this limit in closed form below
//! z = e^{−30}; the laws, their range and their test against the
//! independent 2-D quadrature are in `docs/film-sphere-thin-limit.md`.
//!
//! # References
//! - B.N.J. Persson, "Rolling friction for hard cylinder and sphere on
//!   viscoelastic solid", Eur. Phys. J. E 33 (2010) 327–333, Eq. (17) and
//!   the film factor S.
//! - P.J. Davis, P. Rabinowitz, *Methods of Numerical Integration*, 2nd ed.,
//!   Academic Press 1984, §2.10 (product integration) and §3.9 (contour
//!   shifts for oscillatory integrals).
//! - L.N. Trefethen, *Approximation Theory and Approximation Practice*, SIAM
//!   2013, ch. 8 (Chebyshev interpolation of analytic functions).

pub mod blend;
pub mod integrals;
pub mod moments;
pub mod rows;
