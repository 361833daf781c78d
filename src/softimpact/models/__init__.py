"""Physical models: materials, contact laws, pulses. Pure, SI, no I/O."""
