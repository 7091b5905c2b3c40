"""Operator tools around the graph: the console, the Foxglove bridge, recording, replay, videos."""
