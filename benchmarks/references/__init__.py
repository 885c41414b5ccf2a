"""Reference implementations, written independently of the code under test: the ocean and the hull as a
user would write them in torch or numpy (``ocean_references``, ``hull_references``), and a velocity
prediction of the E-Boat from python-vpp (``vpp_reference``). The performance runs race them; the tests
check against them."""
