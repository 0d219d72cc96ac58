"""Closed forms for the thick-walled cylinder (plane strain) and hollow sphere of an incompressible
isotropic solid with W(I1, I2) = C10 (I1-3) + C01 (I2-3) + C20 (I1-3)^2 + C11 (I1-3)(I2-3) + C02 (I2-3)^2
under internal pressure p (outer surface free). Derivation (Ogden, Non-linear Elastic Deformations,
1984, §5.3; Holzapfel 2000 §7.4 for the sphere):

Radial equilibrium of the Cauchy stress in the deformed body, d sigma_r / dr + k (sigma_r - sigma_t) / r = 0
(k = 1 cylinder, 2 sphere), with sigma_r(a) = -p and sigma_r(b) = 0, gives
    p = int_a^b k (sigma_t - sigma_r) / r dr.
Incompressibility fixes the motion by the inner radius a: r^(k+1) - R^(k+1) = a^(k+1) - A^(k+1), and the
hoop stretch lam = r / R. With w(lam) the strain energy as a function of lam alone,
    cylinder (lam_r = 1/lam, lam_z = 1): w = W(I1, I2), I1 = I2 = lam^2 + lam^-2 + 1,
        sigma_t - sigma_r = lam w'(lam) = 2 (W1 + W2) (lam^2 - lam^-2);
    sphere (lam_r = lam^-2): w = W(I1, I2), I1 = 2 lam^2 + lam^-4, I2 = lam^4 + 2 lam^-2,
        2 (sigma_t - sigma_r) = lam w'(lam) = 4 W1 (lam^2 - lam^-4) + 4 W2 (lam^4 - lam^-2),
where W1 = dW/dI1, W2 = dW/dI2. So in both cases p = int_a^b lam w'(lam) / r dr, evaluated here by
Gauss-Legendre quadrature (200 points: converged to round-off for these smooth integrands).
"""
import numpy as np


def _derivatives(c, i1, i2):
    w1 = c["c10"] + 2 * c["c20"] * (i1 - 3) + c["c11"] * (i2 - 3)
    w2 = c["c01"] + 2 * c["c02"] * (i2 - 3) + c["c11"] * (i1 - 3)
    return w1, w2


def _lam_w_prime(c, lam, sphere):
    if sphere:
        i1, i2 = 2 * lam**2 + lam**-4, lam**4 + 2 * lam**-2
        w1, w2 = _derivatives(c, i1, i2)
        return 4 * w1 * (lam**2 - lam**-4) + 4 * w2 * (lam**4 - lam**-2)
    i = lam**2 + lam**-2 + 1
    w1, w2 = _derivatives(c, i, i)
    return 2 * (w1 + w2) * (lam**2 - lam**-2)


def internal_pressure(c, inner, outer, inner_stretch, sphere, points=200):
    """Pressure (units of c) that stretches the inner radius `inner` by `inner_stretch`."""
    n = 2 if sphere else 1  # r^(n+1) - R^(n+1) is constant
    shift = (inner * inner_stretch) ** (n + 1) - inner ** (n + 1)
    a, b = inner * inner_stretch, (outer ** (n + 1) + shift) ** (1.0 / (n + 1))
    x, w = np.polynomial.legendre.leggauss(points)
    r = 0.5 * (b - a) * x + 0.5 * (b + a)
    lam = r / (r ** (n + 1) - shift) ** (1.0 / (n + 1))
    return 0.5 * (b - a) * np.sum(w * _lam_w_prime(c, lam, sphere) / r)


def neo_hookean_pressure(shear_modulus, inner, outer, inner_stretch, sphere):
    """The same for C10 = mu/2 alone, integrated by hand (dr/r = dlam / (lam (1 - lam^(k+1)))):
    tube p = mu [ln lam + 1/(2 lam^2)] from lam_b to lam_a, sphere p = mu [2/lam + 1/(2 lam^4)] from
    lam_a to lam_b: the independent check of internal_pressure()."""
    n = 2 if sphere else 1
    shift = (inner * inner_stretch) ** (n + 1) - inner ** (n + 1)
    outer_stretch = (outer ** (n + 1) + shift) ** (1.0 / (n + 1)) / outer
    if sphere:
        antiderivative = lambda lam: -2 / lam - 1 / (2 * lam**4)
    else:
        antiderivative = lambda lam: np.log(lam) - 1 / (2 * lam**2)
    return shear_modulus * (antiderivative(inner_stretch) - antiderivative(outer_stretch))
