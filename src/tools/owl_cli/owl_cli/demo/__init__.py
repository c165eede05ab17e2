"""`owl demo`: the course's chapter 4 robot live on the simulated kit, reported in readable lines."""
