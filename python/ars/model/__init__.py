"""The model of the original ARS API: ``ars.model.simulator`` (the simulation),
``ars.model.robot`` (joints, sensors), ``ars.model.collision`` (terrain helpers)."""
