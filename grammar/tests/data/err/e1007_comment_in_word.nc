X1(c)0
X(c)10
G01 X-(c)5
