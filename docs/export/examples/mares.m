function [xdot, U, M, MRB, MA, D, g, DL, DQ, Bthr] = mares(x, tau, Vc)
% MARES  hydrodynamic model exported by stripcoef 0.1.0 to format 'mss'
% Compatible with MATLAB and the free software GNU Octave (www.octave.org).
% Style of Fossen's MSS vehicle models (cybergalactic/MSS VESSELS/models/remus100.m).
% reference point: CO = [0.00436761219642622, 0, 0.0013222898113235168] m (FRD body coordinates of the source model)
% axes: FRD (x forward, y starboard, z down)
% mass 41.31884295489259 kg, volume 0.04169657105299387 m^3, density 998.2063193823999 kg/m^3
%
%   x   = [ u v w p q r x y z phi theta psi ]'  (m/s, rad/s, m, rad), FRD body
%         velocities about the CO above, NED position, Euler angles (zyx)
%   tau = [ X Y Z K M N ]' generalized force about the CO (N, Nm), default zeros
%   Vc  = [ Vn Ve Vd ]' constant ocean current in NED (m/s), default zeros
%
% Returns xdot (12x1), the speed U (m/s), M = MRB + MA, MRB, MA, the damping
% D = DL + DQ*diag(|nu_r|) at the relative velocity nu_r, the restoring forces
% g(eta) (Fossen 2011, eq. 4.6), DL, DQ and the thruster allocation Bthr (6 x n,
% tau = Bthr*T). MA, DL, DQ are positive: -MA*nu_dot - D*nu is the hydrodynamic force.
%
%   M*nu_dot = tau - CRB(nu)*nu - CA(nu_r)*nu_r - D*nu_r - g + MA*nu_c_dot
%
% Example usage:
%   [~,~,M,MRB,MA] = mares()             : the constant matrices
%   [xdot,U] = mares(x, tau)             : no ocean current
%   [xdot,U] = mares(x, tau, [0.2 0 0]') : 0.2 m/s current towards north
%
% Thrusters (columns of Bthr): P1, P2, V1, V2

if nargin < 1 || isempty(x), x = zeros(12,1); end
if nargin < 2 || isempty(tau), tau = zeros(6,1); end
if nargin < 3 || isempty(Vc), Vc = zeros(3,1); end
x = x(:); tau = tau(:); Vc = Vc(:);
if length(x) ~= 12, error('x-vector must have dimension 12'); end
if length(tau) ~= 6, error('tau-vector must have dimension 6'); end
if length(Vc) ~= 3, error('Vc-vector must have dimension 3'); end

% Model parameters (stripcoef)
rho = 998.2063193823999;            % water density (kg/m3)
g_n = 9.81;            % acceleration of gravity (m/s2)
m = 41.31884295489259;                 % mass (kg)
vol = 0.04169657105299387;             % displaced volume (m3)
r_bg = [-0.0004385262757731828; 4.382062755308583e-19; 0.001599977783438195];  % CG w.r.t. the CO (m)
r_bb = [0; 0; 0];  % CB w.r.t. the CO (m)
W = m * g_n; B = rho * g_n * vol;      % weight and buoyancy (N)

% Rigid-body mass matrix about the CO (Fossen 2011, eq. 3.44)
MRB = [
  41.31884295489259, 0, 0, 0, 0.06610923076519992, 0;
  0, 41.31884295489259, 0, -0.06610923076519992, 0, -0.01811939832026606;
  0, 0, 41.31884295489259, 0, 0.01811939832026606, 0;
  0, -0.06610923076519992, 0, 0.22800901836802187, 0, -0.023603777815885154;
  0.06610923076519992, 0, 0.01811939832026606, 0, 6.551168189377223, 0;
  0, -0.01811939832026606, 0, -0.02360377781588516, 0, 6.553644484004887];
% Added mass, positive (MA(1,1) = -X_udot)
MA = [
  3.201186164379057, 0, 0, 0, -0.0020318559695265827, 0;
  0, 41.49864175383854, 0, 0.00398702352372122, 0, 0.1306629877635664;
  0, 0, 38.058058797258695, 0, 0.020500459582069985, 0;
  0, 0.00398702352372122, 0, 0.027790670416801284, 0, -0.009486029389554514;
  -0.0020318559695265827, 0, 0.020500459582069985, 0, 5.12917468673543, 0;
  0, 0.1306629877635664, 0, -0.009486029389554514, 0, 5.522773085725973];
% Linear damping, positive (DL(1,1) = -X_u)
DL = [
  0, 0, 0, 0, 0, 0;
  0, 0.7502294751833387, 0, 0.0005118876781797303, 0, -0.004816386190430477;
  0, 0, 0.7302136304514435, 0, 0.00572971771413495, 0;
  0, 0.0005118876781797303, 0, 0.000346937884956086, 0, -0.00010029824574867386;
  0, 0, 0.00572971771413495, 0, 0.12417977305027816, 0;
  0, -0.004816386190430477, 0, -0.00010029824574867385, 0, 0.1266795151571629];
% Quadratic damping, positive: force_i = -sum_j DQ(i,j)*|nu_j|*nu_j (DQ(1,1) = -X_u|u|)
DQ = [
  6.001271812691849, 0, 0, 0, 0.019969775639467804, 0;
  0, 119.58179044515559, 0, -0.05285886258585152, 0, -1.1994602365473175;
  0, 0, 116.5505706939518, 0, 1.296280804156439, 0;
  0, -0.2584819148576911, 0, 0.02095568492014148, 0, -0.018312249372325756;
  0.14891734067272266, 0, 2.091606772683507, 0, 10.623312572238103, 0;
  0, -1.9532909238580765, 0, -0.010385224108309258, 0, 10.765602964478171];
% Thruster allocation about the CO: tau = Bthr * thrusts (N)
Bthr = [
  1, 1, 0, 0;
  0, 0, 0, 0;
  0, 0, 1, 1;
  0, 0, 0, 0;
  -0.0013222898113235168, -0.0013222898113235168, 0.3043676121964262, -0.3956323878035738;
  0.13, -0.13, 0, 0];

% States, current and relative velocity
nu = x(1:6); eta = x(7:12);
[J, R] = eulerang_local(eta(4), eta(5), eta(6));
nu_c = [R' * Vc; 0; 0; 0];
nu_c_dot = [-cross(nu(4:6), nu_c(1:3)); 0; 0; 0];
nu_r = nu - nu_c;
U = sqrt(nu(1)^2 + nu(2)^2 + nu(3)^2);

M = MRB + MA;
D = DL + DQ * diag(abs(nu_r));
g = gvect_local(W, B, eta(5), eta(4), r_bg, r_bb);
CRB = m2c_local(MRB, nu);
CA = m2c_local(MA, nu_r);

nu_dot = M \ (tau - CRB * nu - CA * nu_r - D * nu_r - g + MA * nu_c_dot);
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
