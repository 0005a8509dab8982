G01 X1 ,X5
(a), (b)
