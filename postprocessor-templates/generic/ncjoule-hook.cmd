@echo off
rem ncjoule hook for Windows CAM systems that can only run a program after posting, or only
rem write into a folder (Mastercam, Vectric, SolidCAM, Estlcam, ...).
rem
rem   ncjoule-hook.cmd FILE...             annotate each FILE in place
rem   ncjoule-hook.cmd /watch FOLDER       annotate every NC file that appears in FOLDER
rem   ncjoule-hook.cmd /watch FOLDER /once annotate what is there now, then exit
rem
rem Settings (environment variables):
rem   NCJOULE          the ncjoule program (default: ncjoule.exe on the PATH; give the .exe,
rem                    not a .bat or .cmd, which cmd.exe would parse again)
rem   NCJOULE_MACHINE  the machine profile: a .toml file or a shipped profile's name (default:
rem                    what ncjoule itself takes: the job file's machine, the user config's
rem                    machine = ..., else its generic profile)
rem   NCJOULE_STOCK    ncjoule's --stock text (optional)
rem   NCJOULE_ARGS     further arguments for "ncjoule annotate" (optional), split at blanks by
rem                    ncjoule itself; cmd.exe never acts on them (& | < > ^ %% ! stay text)
rem   NCJOULE_EXT      watched extensions (default: nc ngc tap cnc gcode nci mpf eia)
rem   NCJOULE_INTERVAL seconds between two looks at the folder (default 2)
rem   NCJOULE_QUIET    a file is taken once its size and time have not changed for more than
rem                    this many seconds by the clock (default 3)
rem   NCJOULE_DISABLE  1 turns the hook off
rem None of them may hold a double quote (it would end the quoting of an argument).
rem
rem The file is annotated with "ncjoule annotate [--machine=PROFILE] --in-place ... -- FILE", which
rem writes through a temporary file: if ncjoule fails or is missing, the file stays as the CAM
rem system wrote it and the hook prints a warning. Whether it was annotated is read from
rem ncjoule's exit code and its status line, never from the file. The hook always exits 0, so a
rem post never fails because of it. In watch mode symbolic links (reparse points) are never
rem followed, and a file ncjoule finds still being written is tried again later.
rem
rem Every value from outside (file names, settings) is expanded with delayed expansion (!var!)
rem only after cmd.exe has parsed the line, so nothing in it can become an operator; file names
rem are read with delayed expansion off, so that a "!" in a name survives.
setlocal EnableExtensions DisableDelayedExpansion

if "%NCJOULE%"=="" set "NCJOULE=ncjoule.exe"
if "%NCJOULE_EXT%"=="" set "NCJOULE_EXT=nc ngc tap cnc gcode nci mpf eia"
if "%NCJOULE_INTERVAL%"=="" set "NCJOULE_INTERVAL=2"
if "%NCJOULE_QUIET%"=="" set "NCJOULE_QUIET=3"
if "%NCJOULE_DISABLE%"=="1" exit /b 0
call :check_settings || exit /b 0

if /i "%~1"=="/watch" goto watch
if "%~1"=="" (
  echo ncjoule-hook: nothing to do: give FILE... or /watch FOLDER 1>&2
  exit /b 0
)

:files
if "%~1"=="" exit /b 0
set "file=%~f1"
call :annotate_file
shift
goto files

rem ---------------------------------------------------------------------------------------------
rem Settings that cmd.exe would otherwise act on are refused: a double quote anywhere, anything
rem but digits in the numbers (set /a evaluates), anything but letters and digits in NCJOULE_EXT.
:check_settings
setlocal EnableDelayedExpansion
set "all=!NCJOULE!!NCJOULE_MACHINE!!NCJOULE_STOCK!!NCJOULE_ARGS!!NCJOULE_EXT!"
set "unquoted=!all:"=!"
if not "!all!"=="!unquoted!" (
  echo ncjoule-hook: warning: a double quote in NCJOULE, NCJOULE_MACHINE, NCJOULE_STOCK, NCJOULE_ARGS or NCJOULE_EXT; nothing is annotated 1>&2
  exit /b 1
)
rem Each text starts with an allowed letter, so that for /f never skips it as a ";" comment.
for /f "delims=x0123456789" %%C in ("x!NCJOULE_INTERVAL!x!NCJOULE_QUIET!") do (
  echo ncjoule-hook: warning: NCJOULE_INTERVAL and NCJOULE_QUIET must be whole seconds; nothing is annotated 1>&2
  exit /b 1
)
for /f "delims=abcdefghijklmnopqrstuvwxyzABCDEFGHIJKLMNOPQRSTUVWXYZ0123456789 " %%C in ("x!NCJOULE_EXT!") do (
  echo ncjoule-hook: warning: NCJOULE_EXT may hold only letters, digits and spaces; nothing is annotated 1>&2
  exit /b 1
)
exit /b 0

rem ---------------------------------------------------------------------------------------------
rem File mode: one file (in "file"); once more after the quiet period when it is still being written.
:annotate_file
setlocal EnableDelayedExpansion
if not exist "!file!" (
  echo ncjoule-hook: warning: !file!: no such file; not annotated 1>&2
  exit /b 1
)
call :take
if "!outcome!"=="busy" (
  del "!err!" 2>nul
  timeout /t !NCJOULE_QUIET! /nobreak >nul
  call :take
)
call :report
exit /b 0

rem ---------------------------------------------------------------------------------------------
rem Runs ncjoule on "file" (delayed expansion on) and sets "outcome": annotated, unchanged,
rem errors (annotated, with errors its controller would refuse), busy (still being written or
rem changed while read: nothing written) or failed; "err" names the file holding its messages.
:take
set "err=%TEMP%\ncjoule-hook-%RANDOM%%RANDOM%.err"
rem Each setting that is given is one quoted argument (a path may hold blanks).
if defined NCJOULE_MACHINE (
  if defined NCJOULE_STOCK (
    "!NCJOULE!" annotate "--machine=!NCJOULE_MACHINE!" --in-place "--stock=!NCJOULE_STOCK!" !NCJOULE_ARGS! -- "!file!" 1>nul 2>"!err!" <nul
  ) else (
    "!NCJOULE!" annotate "--machine=!NCJOULE_MACHINE!" --in-place !NCJOULE_ARGS! -- "!file!" 1>nul 2>"!err!" <nul
  )
) else (
  if defined NCJOULE_STOCK (
    "!NCJOULE!" annotate --in-place "--stock=!NCJOULE_STOCK!" !NCJOULE_ARGS! -- "!file!" 1>nul 2>"!err!" <nul
  ) else (
    "!NCJOULE!" annotate --in-place !NCJOULE_ARGS! -- "!file!" 1>nul 2>"!err!" <nul
  )
)
set "rc=!errorlevel!"
set "outcome=failed"
if "!rc!"=="0" (
  findstr /b /l /c:"ncjoule: annotated " "!err!" >nul 2>nul && set "outcome=annotated"
  findstr /l /c:" unchanged: already annotated this way" "!err!" >nul 2>nul && set "outcome=unchanged"
)
if "!rc!"=="2" (
  findstr /b /l /c:"ncjoule: annotated " "!err!" >nul 2>nul && findstr /l /c:", with errors" "!err!" >nul 2>nul && set "outcome=errors"
)
if "!rc!"=="3" (
  findstr /l /c:"still being written" /c:"changed while" "!err!" >nul 2>nul && set "outcome=busy"
)
exit /b 0

rem Says what became of "file", with ncjoule's messages when it was not annotated.
:report
if "!outcome!"=="annotated" echo ncjoule-hook: annotated !file!
if "!outcome!"=="unchanged" echo ncjoule-hook: !file! unchanged: already annotated this way
if "!outcome!"=="errors" (
  echo ncjoule-hook: warning: !file! annotated, with errors its controller would refuse: 1>&2
  type "!err!" 1>&2
)
if "!outcome!"=="failed" (
  echo ncjoule-hook: warning: !file! not annotated ^(ncjoule exit !rc!^); the file is as it was: 1>&2
  type "!err!" 1>&2
)
if "!outcome!"=="busy" (
  echo ncjoule-hook: warning: !file! not annotated: it is still being written; the file is as it was: 1>&2
  type "!err!" 1>&2
)
del "!err!" 2>nul
exit /b 0

rem ---------------------------------------------------------------------------------------------
:watch
set "folder=%~f2"
set "once=0"
if /i "%~3"=="/once" set "once=1"
if not exist "%folder%\" (
  echo ncjoule-hook: /watch "%folder%": not a folder 1>&2
  exit /b 0
)
rem One state file per watched file, of the same name, in a folder of its own:
rem "STATUS SINCE TRIES SIZE TIME" (seen, done, failed or link; the clock when that size and
rem time were first seen; how often ncjoule found it still being written).
set "state=%TEMP%\ncjoule-hook-%RANDOM%%RANDOM%"
mkdir "%state%" || exit /b 0
:look
set "pending=0"
call :now
for %%E in (%NCJOULE_EXT%) do (
  for %%F in ("%folder%\*.%%E") do (
    set "f=%%~fF"
    set "name=%%~nxF"
    set "attr=%%~aF"
    set "sig=%%~zF %%~tF"
    call :consider
  )
)
if "%once%"=="1" if "%pending%"=="0" (
  rmdir /s /q "%state%" 2>nul
  exit /b 0
)
timeout /t %NCJOULE_INTERVAL% /nobreak >nul
goto look

rem The clock, in seconds since midnight ("now"); a day is added back when it wraps.
:now
for /f "tokens=1-3 delims=:.," %%a in ("%TIME: =0%") do set /a "now=(1%%a-100)*3600+(1%%b-100)*60+(1%%c-100)"
exit /b 0

rem One file of the folder ("f", "name", "attr", "sig") at one look.
:consider
setlocal EnableDelayedExpansion
if "!name:~0,1!"=="." exit /b 0
if "!attr:~0,1!"=="d" exit /b 0
set "status=" & set "since=0" & set "tries=0" & set "old="
set "line="
if exist "!state!\!name!" set /p line=<"!state!\!name!"
if defined line for /f "tokens=1-3*" %%a in ("!line!") do (
  set "status=%%a" & set "since=%%b" & set "tries=%%c" & set "old=%%d"
)
rem A reparse point (symbolic link, junction) is never followed, and named once.
if not "!attr:l=!"=="!attr!" (
  if not "!status!"=="link" echo ncjoule-hook: warning: !f! is a symbolic link; it is not followed and not annotated 1>&2
  >"!state!\!name!" echo link 0 0 -
  exit /b 0
)
if not "!sig!"=="!old!" (
  >"!state!\!name!" echo seen !now! 0 !sig!
  endlocal & set /a "pending+=1"
  exit /b 0
)
if "!status!"=="done" exit /b 0
if "!status!"=="failed" exit /b 0
set /a "quiet_for=now-since"
if !quiet_for! lss 0 set /a "quiet_for+=86400"
if !quiet_for! leq !NCJOULE_QUIET! (
  endlocal & set /a "pending+=1"
  exit /b 0
)
set "file=!f!"
call :take
for %%A in ("!f!") do set "sig=%%~zA %%~tA"
if "!outcome!"=="busy" (
  set /a "tries+=1"
  if "!once!"=="0" set "tries=0"
  if !tries! lss 5 (
    del "!err!" 2>nul
    call :now
    >"!state!\!name!" echo seen !now! !tries! !sig!
    endlocal & set /a "pending+=1"
    exit /b 0
  )
)
call :report
set "status=failed"
if "!outcome!"=="annotated" set "status=done"
if "!outcome!"=="unchanged" set "status=done"
if "!outcome!"=="errors" set "status=done"
>"!state!\!name!" echo !status! 0 0 !sig!
exit /b 0
