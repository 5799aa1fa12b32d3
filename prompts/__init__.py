"""Resource package: data files read with importlib.resources."""
