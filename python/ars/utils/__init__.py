"""Vector and geometry helpers of the original ARS API (tuples in, tuples out)."""
