"""The kitchen world: symbolic state, task inference and repair, and the persona benchmark."""
