"""pool_env: exact, fast pool physics as a Gymnasium environment."""

__version__ = "0.1.0"
