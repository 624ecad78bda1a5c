%
(A Fusion post's start file, MPCNC21.cps: "%" lines as notes between the commands.)
(rs274: "Bad character '%' used". Taken as the closing '%', every cut below vanishes.)
G21 G90
% vfd enable
M3 S5000
G0 X0 Y0 Z3
G1 Z-1 F300
G1 X20 F1000
G0 Z3
% spindle relays off
M5
%%
