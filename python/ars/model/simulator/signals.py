"""Signals a simulation sends (``sender`` is the simulation), around each step and
each frame."""

SIM_PRE_STEP = "simulation pre step"
SIM_POST_STEP = "simulation post step"
SIM_PRE_FRAME = "simulation pre frame"
SIM_POST_FRAME = "simulation post frame"
