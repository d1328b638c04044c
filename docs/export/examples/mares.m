function [xdot, U, M, MRB, MA, D, g, DL, DQ, Bthr, L, Bdelta] = mares(x, tau, Vc, delta)
% MARES  hydrodynamic model exported by stripcoef 0.1.0 to format 'mss'
% Compatible with MATLAB and the free software GNU Octave (www.octave.org).
% Style of Fossen's MSS vehicle models (cybergalactic/MSS CRAFT/AUV/models/remus100.m).
% reference point: CO = [0.00436665486209404, 0, 0.0013222979649128548] m (FRD body coordinates of the source model)
% axes: FRD (x forward, y starboard, z down)
% mass 41.32106391636393 kg, volume 0.04169631394247401 m^3, density 998.2063193823999 kg/m^3
%
%   x   = [ u v w p q r x y z phi theta psi ]'  (m/s, rad/s, m, rad), FRD body
%         velocities about the CO above, NED position, Euler angles (zyx)
%   tau = [ X Y Z K M N ]' generalized force about the CO (N, Nm), default zeros
%   Vc  = [ Vn Ve Vd ]' constant ocean current in NED (m/s), default zeros
%   delta = control surface deflections (rad), one per column of Bdelta, default zeros
%
% Returns xdot (12x1), the speed U (m/s), M = MRB + MA, MRB, MA, the damping
% D = DL + u_r*L + DQ*diag(|nu_r|) at the relative velocity nu_r (L: body and fin
% lift, Prestero 2001 sec. 3.6), the restoring forces g(eta) (Fossen 2011, eq. 4.6),
% DL, DQ, the thruster allocation Bthr (6 x n, tau = Bthr*T), L and the control
% surfaces' Bdelta (force u_r*|u_r|*Bdelta*delta, Prestero 2001 sec. 3.7).
% MA, DL, DQ are positive: -MA*nu_dot - D*nu is the hydrodynamic force.
%
%   M*nu_dot = tau + u_r|u_r| Bdelta delta - CRB(nu)*nu - CA(nu_r)*nu_r - D*nu_r - g
%              + MA*nu_c_dot
%
% Example usage:
%   [~,~,M,MRB,MA] = mares()             : the constant matrices
%   [xdot,U] = mares(x, tau)             : no ocean current
%   [xdot,U] = mares(x, tau, [0.2 0 0]') : 0.2 m/s current towards north
%
% Thrusters (columns of Bthr): P1, P2, V1, V2
% Control surfaces (columns of Bdelta): none

if nargin < 1 || isempty(x), x = zeros(12,1); end
if nargin < 4 || isempty(delta), delta = zeros(0,1); end
delta = delta(:);
if nargin < 2 || isempty(tau), tau = zeros(6,1); end
if nargin < 3 || isempty(Vc), Vc = zeros(3,1); end
x = x(:); tau = tau(:); Vc = Vc(:);
if length(x) ~= 12, error('x-vector must have dimension 12'); end
if length(tau) ~= 6, error('tau-vector must have dimension 6'); end
if length(Vc) ~= 3, error('Vc-vector must have dimension 3'); end

% Model parameters (stripcoef)
rho = 998.2063193823999;            % water density (kg/m3)
g_n = 9.81;            % acceleration of gravity (m/s2)
m = 41.32106391636393;                 % mass (kg)
vol = 0.04169631394247401;             % displaced volume (m3)
r_bg = [-0.0004234878459554864; -2.7025640964143323e-19; 0.001607830407052056];  % CG w.r.t. the CO (m)
r_bb = [0; 0; 0];  % CB w.r.t. the CO (m)
W = m * g_n; B = rho * g_n * vol;      % weight and buoyancy (N)

% Rigid-body mass matrix about the CO (Fossen 2011, eq. 3.44)
MRB = [
  41.32106391636393, 0, 0, 0, 0.06643726301647145, 0;
  0, 41.32106391636393, 0, -0.06643726301647145, 0, -0.017498968350529935;
  0, 0, 41.32106391636393, 0, 0.017498968350529935, 0;
  0, -0.06643726301647145, 0, 0.2280629775480152, 0, -0.02369302548573914;
  0.06643726301647145, 0, 0.017498968350529935, 0, 6.551275412100456, 0;
  0, -0.017498968350529935, 0, -0.023693025485739143, 0, 6.553724319663196];
% Added mass, positive (MA(1,1) = -X_udot)
MA = [
  3.9080205335022757, 0, 0, 0, -0.002031868498488919, 0;
  0, 41.036429297212806, 0, 0.003975713912744219, 0, 0.15571599365549155;
  0, 0, 36.91390605313635, 0, 0.00805582597421888, 0;
  0, 0.003975713912744219, 0, 0.027790670034328287, 0, -0.009278143896206813;
  -0.002031868498488919, 0, 0.00805582597421888, 0, 4.824341228959663, 0;
  0, 0.15571599365549155, 0, -0.009278143896206813, 0, 5.293744731778096];
% Linear damping, positive (DL(1,1) = -X_u)
DL = [
  0, 0, 0, 0, 0, 0;
  0, 0.7501885810374327, 0, 0.0005118397209968547, 0, -0.004819820893470568;
  0, 0, 0.7301727363055358, 0, 0.005733206876093822, 0;
  0, 0.0005118397209968547, 0, 0.00034693782180132216, 0, -0.00010030328636826275;
  0, 0, 0.005733206876093822, 0, 0.12415684895144302, 0;
  0, -0.004819820893470568, 0, -0.00010030328636826277, 0, 0.1266566013908442];
% Quadratic damping, positive: force_i = -sum_j DQ(i,j)*|nu_j|*nu_j (DQ(1,1) = -X_u|u|)
DQ = [
  6.0012083844558894, 0, 0, 0, 0.019969773115173384, 0;
  0, 119.57559739437953, 0, -0.05285886418027026, 0, -1.1998235201929406;
  0, 0, 116.54437764317548, 0, 1.2966503361901387, 0;
  0, -0.25848912889531994, 0, 0.020955683648977017, 0, -0.018312212079145233;
  0.14891737561184415, 0, 2.092129463170924, 0, 10.620700850353032, 0;
  0, -1.9538053670317983, 0, -0.010385274551659671, 0, 10.76299097350171];
% Thruster allocation about the CO: tau = Bthr * thrusts (N)
Bthr = [
  1, 1, 0, 0;
  0, 0, 0, 0;
  0, 0, 1, 1;
  0, 0, 0, 0;
  -0.0013222979649128548, -0.0013222979649128548, 0.304366654862094, -0.395633345137906;
  0.13, -0.13, 0, 0];
% Lift (forward-speed) terms, positive: force = -u*L*nu (L(2,2) = -Y_uv)
L = [
  0, 0, 0, 0, 0, 0;
  0, 0, 0, 0, 0, 0;
  0, 0, 0, 0, 0, 0;
  0, 0, 0, 0, 0, 0;
  0, 0, 0, 0, 0, 0;
  0, 0, 0, 0, 0, 0];
% Control surfaces: force = u*|u|*Bdelta*delta (Bdelta(2,1) = Y_uudr)
Bdelta = zeros(6,0);

% States, current and relative velocity
nu = x(1:6); eta = x(7:12);
[J, R] = eulerang_local(eta(4), eta(5), eta(6));
nu_c = [R' * Vc; 0; 0; 0];
nu_c_dot = [-cross(nu(4:6), nu_c(1:3)); 0; 0; 0];
nu_r = nu - nu_c;
U = sqrt(nu(1)^2 + nu(2)^2 + nu(3)^2);

M = MRB + MA;
D = DL + nu_r(1) * L + DQ * diag(abs(nu_r));
g = gvect_local(W, B, eta(5), eta(4), r_bg, r_bb);
CRB = m2c_local(MRB, nu);
CA = m2c_local(MA, nu_r);

tau_delta = nu_r(1) * abs(nu_r(1)) * (Bdelta * delta);
nu_dot = M \ (tau + tau_delta - CRB * nu - CA * nu_r - D * nu_r - g + MA * nu_c_dot);
xdot = [nu_dot; J * nu];
end


function C = m2c_local(M, nu)
% Coriolis-centripetal matrix of a 6x6 inertia matrix (Fossen 2011, eq. 3.46 / 6.43)
a = M(1:3,1:3) * nu(1:3) + M(1:3,4:6) * nu(4:6);
b = M(4:6,1:3) * nu(1:3) + M(4:6,4:6) * nu(4:6);
C = [zeros(3,3), -smtrx_local(a); -smtrx_local(a), -smtrx_local(b)];
end


function S = smtrx_local(a)
% Skew-symmetric matrix, S(a)*b = cross(a, b) (Fossen 2011, eq. 2.10)
S = [0, -a(3), a(2); a(3), 0, -a(1); -a(2), a(1), 0];
end


function [J, R] = eulerang_local(phi, theta, psi)
% J(eta) with the zyx rotation (Fossen 2011, eqs. 2.18 and 2.29)
cphi = cos(phi); sphi = sin(phi); cth = cos(theta); sth = sin(theta);
cpsi = cos(psi); spsi = sin(psi);
R = [cpsi*cth, -spsi*cphi + cpsi*sth*sphi,  spsi*sphi + cpsi*cphi*sth;
     spsi*cth,  cpsi*cphi + sphi*sth*spsi, -cpsi*sphi + sth*spsi*cphi;
     -sth,      cth*sphi,                   cth*cphi];
if abs(cth) < 1e-9, error('Tzyx is singular for theta = +-90 deg'); end
T = [1, sphi*sth/cth, cphi*sth/cth; 0, cphi, -sphi; 0, sphi/cth, cphi/cth];
J = [R, zeros(3,3); zeros(3,3), T];
end


function g = gvect_local(W, B, theta, phi, r_bg, r_bb)
% Restoring forces of a submerged vehicle (Fossen 2011, eq. 4.6)
sth = sin(theta); cth = cos(theta); sphi = sin(phi); cphi = cos(phi);
g = [ (W-B) * sth;
     -(W-B) * cth * sphi;
     -(W-B) * cth * cphi;
     -(r_bg(2)*W - r_bb(2)*B) * cth * cphi + (r_bg(3)*W - r_bb(3)*B) * cth * sphi;
      (r_bg(3)*W - r_bb(3)*B) * sth + (r_bg(1)*W - r_bb(1)*B) * cth * cphi;
     -(r_bg(1)*W - r_bb(1)*B) * cth * sphi - (r_bg(2)*W - r_bb(2)*B) * sth ];
end
