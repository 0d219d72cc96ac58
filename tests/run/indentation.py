"""Closed forms for a rigid indenter pressed into an elastic layer bonded to a rigid base
(frictionless contact, small strain), shear modulus G, bulk modulus K, Poisson's ratio
nu = (3K - 2G) / (2 (3K + G)), Young's modulus E = 2 G (1 + nu).

Flat-ended cylindrical punch of radius a, depth delta, layer thickness h: Boussinesq's half-space
force F = 2 E a delta / (1 - nu^2) (Johnson, Contact Mechanics, 1985, §3.8; 8 G a delta for
nu = 1/2) times the bonded layer's correction for nu = 1/2 (Garcia & Garcia 2018, Biophys. J.
114:2923, flat punch): 1 + 1.133 x + 1.283 x^2 + 0.598 x^3 - 0.291 x^4, x = a/h.

Sphere of radius R: Hertz's F = 4 E / (3 (1 - nu^2)) R^(1/2) delta^(3/2) times the bonded layer's
correction of Dimitriadis et al. 2002 (Biophys. J. 82:2798, eqs. 11-12), chi = sqrt(R delta)/h:
1 - (2 a0/pi) chi + (4 a0^2/pi^2) chi^2 - (8/pi^3)(a0^3 + 4 pi^2 b0/15) chi^3
  + (16 a0/pi^4)(a0^3 + 3 pi^2 b0/5) chi^4,
a0 = -(1.2876 - 1.4678 nu + 1.3442 nu^2)/(1 - nu), b0 = (0.6387 - 1.0277 nu + 1.5164 nu^2)/(1 - nu).
"""
import math


def poisson_ratio(shear_modulus, bulk_modulus):
    return (3 * bulk_modulus - 2 * shear_modulus) / (2 * (3 * bulk_modulus + shear_modulus))


def flat_punch_force(shear_modulus, bulk_modulus, radius, depth, thickness):
    nu = poisson_ratio(shear_modulus, bulk_modulus)
    youngs = 2 * shear_modulus * (1 + nu)
    x = radius / thickness
    layer = 1 + 1.133 * x + 1.283 * x**2 + 0.598 * x**3 - 0.291 * x**4
    return 2 * youngs * radius * depth / (1 - nu**2) * layer


def sphere_force(shear_modulus, bulk_modulus, radius, depth, thickness):
    nu = poisson_ratio(shear_modulus, bulk_modulus)
    youngs = 2 * shear_modulus * (1 + nu)
    a0 = -(1.2876 - 1.4678 * nu + 1.3442 * nu**2) / (1 - nu)
    b0 = (0.6387 - 1.0277 * nu + 1.5164 * nu**2) / (1 - nu)
    chi = math.sqrt(radius * depth) / thickness
    pi = math.pi
    layer = (1 - 2 * a0 / pi * chi + 4 * a0**2 / pi**2 * chi**2
             - 8 / pi**3 * (a0**3 + 4 * pi**2 * b0 / 15) * chi**3
             + 16 * a0 / pi**4 * (a0**3 + 3 * pi**2 * b0 / 5) * chi**4)
    return 4 * youngs / (3 * (1 - nu**2)) * math.sqrt(radius) * depth**1.5 * layer
