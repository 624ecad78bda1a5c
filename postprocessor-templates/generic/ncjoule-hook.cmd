@echo off
rem ncjoule hook for Windows CAM systems that can only run a program after posting, or only
rem write into a folder (Mastercam, Vectric, SolidCAM, Estlcam, ...).
rem
rem   ncjoule-hook.cmd FILE...             annotate each FILE in place
rem   ncjoule-hook.cmd /watch FOLDER       annotate every NC file that appears in FOLDER
rem   ncjoule-hook.cmd /watch FOLDER /once annotate what is there now, then exit
rem
rem Settings (environment variables, or edit the defaults below):
rem   NCJOULE          the ncjoule program (default: ncjoule.exe on the PATH)
rem   NCJOULE_MACHINE  the machine profile (.toml) - required
rem   NCJOULE_STOCK    ncjoule's --stock text (optional)
rem   NCJOULE_ARGS     further arguments for "ncjoule annotate" (optional)
rem   NCJOULE_EXT      watched extensions (default: nc ngc tap cnc gcode nci mpf eia)
rem   NCJOULE_INTERVAL seconds between two looks at the folder (default 2)
rem   NCJOULE_DISABLE  1 turns the hook off
rem
rem The file is annotated with "ncjoule annotate FILE --machine PROFILE --in-place", which writes
rem through a temporary file: if ncjoule fails or is missing, the file stays as the CAM system
rem wrote it and the hook prints a warning. The hook always exits 0, so a post never fails
rem because of it. In watch mode a file is taken once its size and time stopped changing, and
rem files that already carry ncjoule's annotations are skipped.
setlocal EnableExtensions EnableDelayedExpansion

if "%NCJOULE%"=="" set "NCJOULE=ncjoule.exe"
if "%NCJOULE_EXT%"=="" set "NCJOULE_EXT=nc ngc tap cnc gcode nci mpf eia"
if "%NCJOULE_INTERVAL%"=="" set "NCJOULE_INTERVAL=2"
if "%NCJOULE_DISABLE%"=="1" exit /b 0

if /i "%~1"=="/watch" goto watch
if "%~1"=="" (
  echo ncjoule-hook: nothing to do: give FILE... or /watch FOLDER 1>&2
  exit /b 0
)

:files
if "%~1"=="" exit /b 0
call :annotate "%~f1"
shift
goto files

rem ---------------------------------------------------------------------------------------------
:annotate
set "file=%~1"
if not exist "%file%" (
  echo ncjoule-hook: warning: %file%: no such file; not annotated 1>&2
  exit /b 1
)
if "%NCJOULE_MACHINE%"=="" (
  echo ncjoule-hook: warning: %file% not annotated: set NCJOULE_MACHINE to the machine profile 1>&2
  exit /b 1
)
set "stockarg="
if not "%NCJOULE_STOCK%"=="" set stockarg=--stock "%NCJOULE_STOCK%"
"%NCJOULE%" annotate --machine "%NCJOULE_MACHINE%" --in-place !stockarg! %NCJOULE_ARGS% -- "%file%" 1>nul 2>"%TEMP%\ncjoule-hook.err"
set "rc=!errorlevel!"
if "!rc!"=="2" (
  findstr /r /c:"NCJ TOTAL" "%file%" >nul 2>nul && (
    echo ncjoule-hook: warning: %file% annotated, with errors its controller would refuse: 1>&2
    type "%TEMP%\ncjoule-hook.err" 1>&2
    del "%TEMP%\ncjoule-hook.err" 2>nul
    exit /b 0
  )
)
if not "!rc!"=="0" (
  echo ncjoule-hook: warning: %file% not annotated ^(ncjoule exit !rc!^); the file is as it was: 1>&2
  type "%TEMP%\ncjoule-hook.err" 1>&2
  del "%TEMP%\ncjoule-hook.err" 2>nul
  exit /b 1
)
del "%TEMP%\ncjoule-hook.err" 2>nul
echo ncjoule-hook: annotated %file%
exit /b 0

rem ---------------------------------------------------------------------------------------------
:watch
set "folder=%~f2"
set "once=0"
if /i "%~3"=="/once" set "once=1"
if not exist "%folder%\" (
  echo ncjoule-hook: /watch %folder%: not a folder 1>&2
  exit /b 0
)
rem seen[file] holds "size time" from the last look; done[file] the same once handled.
:look
set "pending=0"
for %%E in (%NCJOULE_EXT%) do (
  for %%F in ("%folder%\*.%%E") do (
    set "name=%%~nxF"
    if not "!name:~0,1!"=="." call :consider "%%~fF" "%%~zF %%~tF"
  )
)
if "%once%"=="1" if "!pending!"=="0" exit /b 0
timeout /t %NCJOULE_INTERVAL% /nobreak >nul
goto look

:consider
set "f=%~1"
set "sig=%~2"
set "key=%f::=_%"
set "key=!key:\=_!"
set "key=!key: =_!"
if defined done_!key! (
  if "!done_%key%!"=="%sig%" exit /b 0
)
findstr /i /r /c:"(NCJ .* CK=" /c:";NCJ .* CK=" "%f%" >nul 2>&1
if not errorlevel 1 (
  set "done_!key!=%sig%"
  exit /b 0
)
if "!seen_%key%!"=="%sig%" (
  call :annotate "%f%"
  for %%A in ("%f%") do set "done_!key!=%%~zA %%~tA"
  exit /b 0
)
set "seen_!key!=%sig%"
set /a pending+=1
exit /b 0
