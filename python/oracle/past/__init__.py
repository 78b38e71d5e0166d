"""Beyond the thesis (issue 40): questions about the past, the state summary, the user's routines."""
