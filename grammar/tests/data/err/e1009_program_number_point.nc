O1.5
:2.
O3.0 (an integer is needed: E1009, not E1004)
