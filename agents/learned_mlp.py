"""Small torch MLPs of the learned nets: built, stepped, and read out as the NumPy arrays the players load."""

from __future__ import annotations

import numpy as np


def descend(opt, loss) -> float:
    """One step of the optimiser `opt` down the torch `loss`; the loss as a float."""
    opt.zero_grad()
    loss.backward()
    opt.step()
    return float(loss.detach())


def torch_mlp(features, hidden) -> tuple:
    """(the feature rows standardised as a torch tensor, their mean, their std, a torch MLP of
    tanh layers `hidden` with one linear output, freshly initialised from torch's generator)."""
    import torch

    x = np.asarray(features, dtype=np.float32)
    mean, std = x.mean(axis=0), x.std(axis=0) + 1e-3
    sizes = (x.shape[1], *hidden, 1)
    layers = []
    for i in range(len(sizes) - 1):
        layers += [torch.nn.Linear(sizes[i], sizes[i + 1]), torch.nn.Tanh()]
    return torch.from_numpy((x - mean) / std), mean, std, torch.nn.Sequential(*layers[:-1])


def mlp_arrays(model, mean, std) -> dict:
    """The NumPy arrays (mean, std, w0, b0, ...) of a `torch_mlp` model and its inputs' standardisation."""
    import torch

    arrays = {"mean": mean, "std": std}
    for n, m in enumerate(m for m in model if isinstance(m, torch.nn.Linear)):
        arrays[f"w{n}"] = m.weight.detach().numpy().T.copy()
        arrays[f"b{n}"] = m.bias.detach().numpy().copy()
    return arrays
