(A post that swaps X and Y without swapping G2 and G3: each quarter circle of a round hole)
(is written as a three-quarter turn. The controller runs it the long way round, three times)
(the path.)
G21 G90 G17
G00 Z5
G00 Y10 X0
G01 Z-1 F100
G03 Y0 X10 J-10 I0 F600
G03 Y-10 X0 J0 I-10
G03 Y0 X-10 J10 I0
G03 Y10 X0 J0 I10
G03 Y0 X10 J-10 I0
G03 Y-10 X0 J0 I-10
G03 Y0 X-10 J10 I0
G03 Y10 X0 J0 I10
G03 Y0 X10 J-10 I0
G03 Y-10 X0 J0 I-10
G03 Y0 X-10 J10 I0
G03 Y10 X0 J0 I10
G00 Z5
M30
