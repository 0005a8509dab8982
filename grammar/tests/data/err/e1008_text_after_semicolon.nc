T0505 ;bedame de 3mm
G00 X1
