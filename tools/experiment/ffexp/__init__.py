"""frictionfield experiment program: the 180-trial study and its analysis."""
VERSION = "1.0.0"
