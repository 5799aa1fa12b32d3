"""The 2D scene: a producer of facts built on the KB (the interaction simulator's model)."""
