function [estimate, info] = spdfit_call(command, nout, varargin)
%SPDFIT_CALL  Internal to the spdfit package: calls the MEX function spdfit_mex.
%   The package's functions (spdfit.fit, spdfit.nearest, spdfit.solve) call it with the number of
%   outputs their caller asked for (INFO is made only when asked for). It converts string
%   arguments to character vectors, raises the MEX function's errors with their identifiers
%   (spdfit:UsageError, spdfit:DataError, spdfit:NumericalError) and the library's message, and
%   raises the library's warnings with theirs (spdfit:rankDeficient, ...), without Octave's and
%   MATLAB's "called from" trace.
for k = 1:numel(varargin)
  if isa(varargin{k}, 'string')
    varargin{k} = char(varargin{k});
  end
end
try
  [estimate, info, warnings] = spdfit_mex(command, nout > 1, varargin{:});
catch err
  message = regexprep(err.message, '^spdfit_mex: ', '');
  error(struct('message', message, 'identifier', err.identifier));
end
if ~isempty(warnings)
  % The library's warnings are about the data, not the code that called: no "called from" trace
  % (the backtrace is off for these only, and back as it was after them, even when a warning was
  % turned into an error). Their identifiers silence each kind: warning('off', 'spdfit:rankDeficient').
  state = warning('query', 'backtrace');
  restore = onCleanup(@() warning(state.state, 'backtrace'));
  warning('off', 'backtrace');
  for k = 1:size(warnings, 1)
    warning(warnings{k, 1}, '%s', warnings{k, 2});
  end
end
end
