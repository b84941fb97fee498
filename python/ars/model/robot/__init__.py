"""Robot parts of the original ARS API: joints and sensors."""
