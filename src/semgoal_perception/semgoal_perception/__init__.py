"""Seeing for itself: block poses and the semantic state from an RGB-D camera (torch, no MuJoCo)."""
