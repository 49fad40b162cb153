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


def fit_outputs(inputs, labels, outputs: int, loss, hidden, epochs: int, seed: int, lr: float, log, name: str) -> dict:
    """The NumPy arrays of a `torch_mlp` with `outputs` linear outputs, fitted on one torch thread
    (the same net from the same data) to minimise `loss(out, labels)` with Adam over shuffled
    minibatches of 512 rows; `log` (if not None) gets the mean loss every 5 epochs."""
    import torch

    torch.set_num_threads(1)
    torch.manual_seed(seed)
    x, mean, std, model = torch_mlp(inputs, hidden)
    model[-1] = torch.nn.Linear(model[-1].in_features, outputs)  # drawn after the one-output layer
    y = torch.from_numpy(np.asarray(labels, dtype=np.float32))
    opt = torch.optim.Adam(model.parameters(), lr=lr)
    gen = torch.Generator().manual_seed(seed)
    for epoch in range(epochs):
        total, order = 0.0, torch.randperm(len(x), generator=gen)
        for b in range(0, len(x), 512):
            idx = order[b:b + 512]
            total += descend(opt, loss(model(x[idx]), y[idx])) * len(idx)
        if log is not None and (epoch + 1) % 5 == 0:
            log(f"{name}: epoch {epoch + 1}/{epochs}, loss {total / len(x):.4f}")
    return mlp_arrays(model, mean, std)


class NumpyMLP:
    """An MLP in NumPy (tanh hidden layers, linear outputs, the inputs standardised) of the
    arrays mean, std, w0, b0, ...: `__call__` of input rows gives their outputs (N, outputs)."""

    def __init__(self, arrays: dict):
        self.arrays = {k: np.asarray(v, dtype=np.float32) for k, v in arrays.items()}
        self.layers = sorted(int(k[1:]) for k in self.arrays if k.startswith("w"))

    @property
    def inputs(self) -> int:
        """How many input columns it reads."""
        return int(self.arrays["mean"].shape[-1])

    def __call__(self, x) -> np.ndarray:
        x = np.asarray(x, dtype=np.float32)
        if x.ndim != 2 or x.shape[1] != self.inputs:
            raise ValueError(f"this net reads rows of {self.inputs} inputs, not an array of shape {x.shape}")
        h = (x - self.arrays["mean"]) / self.arrays["std"]
        for n in self.layers:
            h = h @ self.arrays[f"w{n}"] + self.arrays[f"b{n}"]
            if n != self.layers[-1]:
                h = np.tanh(h)
        return h
