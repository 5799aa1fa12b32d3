"""Resource package: the evaluation sets shipped with situated (huric/: the HuRIC development set),
read with importlib.resources."""
