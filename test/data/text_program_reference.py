#!/usr/bin/python3
"""The textbook's bouncing-rod program (Euler-Cromer), run headless with numpy for fixed theta0.

The loop below is the text's, statement for statement; only the plotting is removed, `pylab` is
replaced by the numpy names it re-exports, and theta[0] = 2*pi*random.rand(1) is replaced by fixed
values. Writes text_program_reference.csv next to this script (read by test_rod.cpp).

Rows: every 20th step over the first 3 s, every 100th step after, and the last sample.
Columns: theta0, i (step index), t, x, y, theta, vx, vy, omega, each float in Python's shortest
round-trip form (repr), so strtod reads back the exact double.

Run: /usr/bin/python3 test/data/text_program_reference.py
"""
import os
from typing import Any, Tuple

from numpy import array, cos, cross, pi, sin, zeros

THETA0S = [0.0, 0.3, 1.0, pi / 2, 2.5, 4.0, 5.5]


# The text's own layout (several statements a line, its names), kept so that it reads against the text:
# flake8 leaves this file's layout alone (setup.cfg).
def text_program(theta0: float) -> Tuple[int, Any, Any, Any, Any, Any]:
    m = 0.5; g = 9.8; h0 = 4.0; L = 1.0; time = 10.0; dt = 0.001; k = 1000.0; v0 = 2.0
    I = (1.0/12.0)*m*L**2
    n = int(round(time/dt))
    r = zeros((n,3),float); v = zeros((n,3),float); theta = zeros(n,float); omega = zeros(n,float); t = zeros(n,float)
    r[0] = array([0,h0,0]); v[0] = array([v0,0,0]); theta[0] = theta0
    for i in range(n-1):
        fnet = array([0,0,0])
        tnet = 0.0
        u = array([cos(theta[i]),sin(theta[i]),0])
        rr = r[i] + 0.5*L*u          # end A
        dr = rr[1]
        f = -k*dr*(dr<0.0)*array([0,1,0])
        fnet = fnet + f
        torque = cross((rr-r[i]),f)
        tnet = tnet + torque
        rr = r[i] - 0.5*L*u          # end B
        dr = rr[1]
        f = -k*dr*(dr<0.0)*array([0,1,0])
        fnet = fnet + f
        torque = cross((rr-r[i]),f)
        tnet = tnet + torque
        fnet = fnet - m*g*array([0,1,0])
        a = fnet/m
        v[i+1] = v[i] + a*dt
        r[i+1] = r[i] + v[i+1]*dt
        alphaz = tnet[2]/I  # type: ignore[index]  # tnet: 0.0 plus arrays, as in the text
        omega[i+1] = omega[i] + alphaz*dt
        theta[i+1] = theta[i] + omega[i+1]*dt
        t[i+1] = t[i] + dt
    return n, t, r, v, theta, omega


def kept(i: int, n: int) -> bool:
    return (i % 20 == 0 and i <= 3000) or i % 100 == 0 or i == n - 1


def main() -> None:
    path = os.path.join(os.path.dirname(os.path.abspath(__file__)), "text_program_reference.csv")
    with open(path, "w") as out:
        out.write("theta0,i,t,x,y,theta,vx,vy,omega\n")
        for theta0 in THETA0S:
            n, t, r, v, theta, omega = text_program(theta0)
            for i in range(n):
                if kept(i, n):
                    row = [theta0, t[i], r[i][0], r[i][1], theta[i], v[i][0], v[i][1], omega[i]]
                    vals = [repr(float(x)) for x in row]
                    out.write(",".join([vals[0], str(i)] + vals[1:]) + "\n")


if __name__ == "__main__":
    main()
