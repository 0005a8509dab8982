n10 g01 x10 z-5 f100
#1=#2 mod 3
if [#1 eq 1] goto 10
while[#1lt3]do1
end1
