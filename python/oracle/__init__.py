"""neem-oracle: KnowRob-compatible NEEM store, Prolog bridge and PreferenceOracle."""

__version__ = "0.1.0"
