"""Beyond the thesis (docs/beyond.md): questions about the past, the state summary, the user's routines."""
