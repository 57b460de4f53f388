function test_thesis_experiment()
% examples/matlab/thesis_experiment2.m (the thesis' M-file with spdfit.fit in place of its
% estimators) against `spdfit experiment thesis` at the same noise: independent random draws, so
% each method's mean must agree within 4 standard errors of the difference (a false alarm in about
% 1 of 2,600 runs for the six methods together).
cli = getenv('SPDFIT_CLI');
trials = 300;
mine = thesis_experiment2(trials, 7);
[status, out] = system(sprintf('"%s" experiment thesis --noise-var %.10g --trials %d --json 2>/dev/null', cli, ...
                               3.2^2 / 12, trials));
assert(status == 0, 'spdfit experiment thesis failed');
ref = jsondecode(out);
names = fieldnames(mine);
for k = 1:numel(names)
  a = mine.(names{k});
  b = ref.methods.(names{k});
  se = sqrt(a.standard_error^2 + b.standard_error^2);
  assert(abs(a.mean - b.mean) <= 4 * se, sprintf('%s: Octave mean %.4f, CLI mean %.4f, 4 s.e. = %.4f', ...
                                                 names{k}, a.mean, b.mean, 4 * se));
  fprintf('%-10s Octave %.4f +- %.4f   CLI %.4f +- %.4f\n', names{k}, a.mean, a.standard_error, b.mean, ...
          b.standard_error);
end
disp('test_thesis_experiment: all passed');
end
