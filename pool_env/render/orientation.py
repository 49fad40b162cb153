"""Ball orientations for the spin markers: identity rotations, and their exact advance under an angular velocity."""

from __future__ import annotations

import numpy as np


def identity_orientation(n: int) -> np.ndarray:
    """(n,3,3) stack of identity rotations."""
    return np.tile(np.eye(3), (int(n), 1, 1))


def integrate_orientation(orientation: np.ndarray, w: np.ndarray, dt: float) -> np.ndarray:
    """Advance (N,3,3) body->world rotations by world-frame angular velocity w (N,3) over dt.

    Exact for constant w: R(t+dt) = exp(dt [w]x) R(t), with the exponential by Rodrigues'
    formula. A single Bjorck step then removes accumulated round-off so repeated
    integration stays orthonormal. Returns a new array.
    """
    rot = np.asarray(orientation, dtype=np.float64).reshape(-1, 3, 3)
    phi = np.broadcast_to(np.asarray(w, dtype=np.float64), (len(rot), 3)) * float(dt)
    theta = np.sqrt(np.einsum("ni,ni->n", phi, phi))
    # sin(t)/t and (1-cos t)/t^2 = 0.5*(sin(t/2)/(t/2))^2, both smooth through t = 0.
    a = np.sinc(theta / np.pi)[:, None, None]
    b = 0.5 * np.sinc(theta / (2 * np.pi))[:, None, None] ** 2
    kx = np.zeros((len(rot), 3, 3))
    kx[:, 0, 1], kx[:, 0, 2] = -phi[:, 2], phi[:, 1]
    kx[:, 1, 0], kx[:, 1, 2] = phi[:, 2], -phi[:, 0]
    kx[:, 2, 0], kx[:, 2, 1] = -phi[:, 1], phi[:, 0]
    step = np.eye(3) + a * kx + b * (kx @ kx)
    out = step @ rot
    # Bjorck orthonormalisation step: X <- X (3I - X^T X) / 2.
    out = 1.5 * out - 0.5 * out @ (np.swapaxes(out, 1, 2) @ out)
    return out
