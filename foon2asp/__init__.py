"""foon2asp: minimal, well-founded FOON task trees with answer-set programming."""

__version__ = "0.1.0"
