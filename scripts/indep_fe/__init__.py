"""indep_fe: an independent Python (numpy + scikit-fem) implementation of the explicit
plane-strain impact solver contract in solver/ALGORITHM.md, used as a code-to-code reference.

It shares no code with the Rust crate; it is written from ALGORITHM.md alone.
"""

__all__ = ["scene", "mesh", "elements", "material", "contact", "solver"]
