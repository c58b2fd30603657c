"""bladefem: finite-element natural frequencies and mode shapes of rotating wind-turbine blades and towers."""

__version__ = "0.1.0"
