"""Collision helpers of the original ARS API."""
