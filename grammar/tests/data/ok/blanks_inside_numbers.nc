X 3 0 . 5 Z - 1 . 2 5
F 0.25
g 0 1 x 1 0
G O T O 1 0
